// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/serve/scene_store.h"

#include <algorithm>
#include <atomic>
#include <fstream>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/plain_name.h"
#include "lmk/serve/api_error.h"

namespace lmk::serve {
namespace {

// An uploaded file's name is only a label and the key to its format: a plain file name.
void check_upload_name(const std::string& name) {
  if (!is_plain_name(name, 200)) {
    throw bad_request("upload: name '" + printable(name) +
                      "' must be a plain file name (letters, digits, '-', '_', '.', not starting "
                      "with '.' or '-') ending in .pcd, .ply or .xyz");
  }
}

}  // namespace

SceneStore::SceneStore(UploadLimits limits, std::filesystem::path scratch_dir,
                       std::optional<DepthCorrection> correction)
    : limits_(limits), scratch_dir_(std::move(scratch_dir)), correction_(std::move(correction)) {}

Scene& SceneStore::insert(std::string name, std::string source, PointCloud cloud) {
  Scene scene;
  scene.id = std::to_string(next_id_++);
  scene.name = std::move(name);
  scene.source = std::move(source);
  scene.cloud = std::make_shared<const PointCloud>(std::move(cloud));
  scenes_.push_back(std::move(scene));
  return scenes_.back();
}

Scene SceneStore::add_file(const std::string& path) {
  PointCloud cloud = read_cloud(path);
  try {
    if (correction_) correction_->apply(cloud);
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
  std::lock_guard<std::mutex> lock(mutex_);
  return insert(std::filesystem::path(path).filename().string(), "file", std::move(cloud));
}

Scene SceneStore::add_upload(const std::string& name, const std::string& bytes) {
  check_upload_name(name);
  try {
    format_from_path(name);
  } catch (const Error& e) {
    throw bad_request(std::string("upload: ") + e.what());
  }
  // The readers work on files: parse in the private scratch directory under a name of our own,
  // then remove it, whatever happens.
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path file =
      scratch_dir_ /
      ("upload-" + std::to_string(counter++) + std::filesystem::path(name).extension().string());
  PointCloud cloud;
  try {
    {
      std::ofstream out(file, std::ios::binary);
      out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      if (!out) throw Error("cannot write the upload to " + scratch_dir_.string());
    }
    cloud = read_cloud(file.string());
    if (correction_) correction_->apply(cloud);
  } catch (const Error& e) {
    std::error_code ignored;
    std::filesystem::remove(file, ignored);
    // The reader names our scratch file; the user knows the upload by its own name.
    std::string message = e.what();
    const std::string ours = file.string();
    if (message.rfind(ours, 0) == 0) message = name + message.substr(ours.size());
    throw bad_request("upload: " + message);
  }
  std::error_code ignored;
  std::filesystem::remove(file, ignored);
  if (cloud.size() > limits_.max_points) {
    throw ApiError(413, "upload: " + name + " holds " + std::to_string(cloud.size()) +
                            " points; at most " + std::to_string(limits_.max_points) +
                            " per upload");
  }

  // The oldest uploads go until this one fits: in count and in points kept. A search under way
  // keeps its own reference to its cloud.
  std::lock_guard<std::mutex> lock(mutex_);
  const auto is_upload = [](const Scene& s) { return s.source == "upload"; };
  const auto over = [&] {
    std::size_t count = 0, points = cloud.size();
    for (const Scene& s : scenes_) {
      if (!is_upload(s)) continue;
      ++count;
      points += s.cloud->size();
    }
    return count > 0 && ((limits_.max_uploads > 0 && count >= limits_.max_uploads) ||
                         points > limits_.max_kept_points);
  };
  while (over()) scenes_.erase(std::find_if(scenes_.begin(), scenes_.end(), is_upload));
  return insert(name, "upload", std::move(cloud));
}

Scene SceneStore::get(const std::string& id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const Scene& s : scenes_) {
    if (s.id == id) return s;
  }
  std::string ids;
  for (const Scene& s : scenes_) ids += (ids.empty() ? "" : ", ") + s.id;
  throw not_found("no scene '" + printable(id, kEchoedBytes) +
                  "' (scenes: " + (ids.empty() ? "none" : ids) + ")");
}

std::vector<Scene> SceneStore::list() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return scenes_;
}

}  // namespace lmk::serve
