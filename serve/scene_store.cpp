// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/serve/scene_store.h"

#include <algorithm>
#include <atomic>
#include <fstream>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/plain_name.h"
#include "lmk/search/find_settings.h"
#include "lmk/search/internal/find_settings_json.h"
#include "lmk/search/scene_footprint.h"
#include "lmk/serve/api_error.h"

namespace lmk::serve {
namespace {

// Footprints remembered, by scene and settings: forgotten all at once past it.
constexpr std::size_t kMaxFootprints = 256;

// An uploaded file's name is only a label and the key to its format: a plain file name.
void check_upload_name(const std::string& name) {
  if (!is_plain_name(name, 200)) {
    throw bad_request("upload: name '" + printable(name) +
                      "' must be a plain file name (letters, digits, '-', '_', '.', not starting "
                      "with '.' or '-') ending in .pcd, .ply or .xyz");
  }
}

std::size_t resident_bytes(const PointCloud& c) {
  return c.points.capacity() * sizeof(Eigen::Vector3f) +
         c.normals.capacity() * sizeof(Eigen::Vector3f) + c.colors.capacity() * sizeof(Color) +
         c.labels.capacity() * sizeof(std::int32_t);
}

}  // namespace

UploadFile::UploadFile(std::string name, std::filesystem::path path)
    : name_(std::move(name)), path_(std::move(path)), file_(std::fopen(path_.c_str(), "wb")) {
  if (file_ == nullptr)
    throw Error("cannot create an upload file in " + path_.parent_path().string());
}

UploadFile::~UploadFile() {
  if (file_ != nullptr) std::fclose(file_);
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);
}

void UploadFile::write(const char* data, std::size_t n) {
  if (file_ == nullptr || std::fwrite(data, 1, n, file_) != n) {
    throw Error("cannot write the upload to " + path_.parent_path().string());
  }
  bytes_ += n;
}

std::size_t UploadFile::close() {
  if (file_ != nullptr) {
    const bool flushed = std::fclose(file_) == 0;
    file_ = nullptr;
    if (!flushed) throw Error("cannot write the upload to " + path_.parent_path().string());
  }
  return bytes_;
}

SceneStore::SceneStore(UploadLimits limits, std::filesystem::path scratch_dir, MemoryBudget& budget,
                       std::optional<DepthCorrection> correction)
    : limits_(limits),
      budget_(budget),
      scratch_dir_(std::move(scratch_dir)),
      correction_(std::move(correction)) {}

Scene& SceneStore::insert(std::string name, std::string source, PointCloud cloud,
                          MemoryBudget::Reservation memory) {
  // The scene's cloud carries its reservation: the memory is given back when the last holder of
  // the cloud (the store, or a job under way after the store let it go) drops it.
  struct Held {
    PointCloud cloud;
    MemoryBudget::Reservation memory;
  };
  auto held = std::make_shared<Held>(Held{std::move(cloud), std::move(memory)});
  Scene scene;
  scene.id = std::to_string(next_id_++);
  scene.name = std::move(name);
  scene.source = std::move(source);
  scene.cloud = std::shared_ptr<const PointCloud>(held, &held->cloud);
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
  MemoryBudget::Reservation memory = budget_.reserve_anyway(resident_bytes(cloud), "scenes");
  std::lock_guard<std::mutex> lock(mutex_);
  return insert(std::filesystem::path(path).filename().string(), "file", std::move(cloud),
                std::move(memory));
}

std::unique_ptr<UploadFile> SceneStore::new_upload_file(const std::string& name) const {
  if (name.empty()) {
    throw bad_request("upload: give the file name as ?name=FILE.pcd (its extension is the format)");
  }
  check_upload_name(name);
  try {
    format_from_path(name);
  } catch (const Error& e) {
    throw bad_request(std::string("upload: ") + e.what());
  }
  // The readers work on files: the bytes go to the private scratch directory under a name of our
  // own, removed whatever happens.
  static std::atomic<unsigned> counter{0};
  return std::make_unique<UploadFile>(
      name, scratch_dir_ / ("upload-" + std::to_string(counter++) +
                            std::filesystem::path(name).extension().string()));
}

Scene SceneStore::add_upload(const std::string& name, const std::string& bytes) {
  const std::unique_ptr<UploadFile> file = new_upload_file(name);
  file->write(bytes.data(), bytes.size());
  return add_upload(*file);
}

Scene SceneStore::add_upload(UploadFile& file) {
  const std::string& name = file.name();
  const std::size_t size = file.close();
  const std::string path = file.path().string();
  // The reader names our scratch file; the user knows the upload by its own name.
  const auto in_their_words = [&](const Error& e) {
    std::string message = e.what();
    if (message.rfind(path, 0) == 0) message = name + message.substr(path.size());
    return "upload: " + message;
  };
  // Priced before it is read: the file's bytes (read whole) and the points it may hold.
  std::size_t points = std::min(size / kLeastXyzPointBytes, limits_.max_points);
  std::size_t decoded_point_bytes = 0;
  try {
    if (const std::optional<DeclaredCloud> declared = declared_cloud(path)) {
      if (declared->points > limits_.max_points) {
        throw ApiError(413, "upload: " + name + " declares " + std::to_string(declared->points) +
                                " points; at most " + std::to_string(limits_.max_points) +
                                " per upload");
      }
      points = declared->points;
      decoded_point_bytes = declared->decoded_point_bytes;
    }
  } catch (const Error& e) {
    throw bad_request(in_their_words(e));
  }
  MemoryBudget::Reservation memory = budget_.reserve(
      cloud_read_price(size, points, decoded_point_bytes), "uploads", "upload " + name);
  PointCloud cloud;
  try {
    cloud = read_cloud(path, limits_.max_points);
    if (correction_) correction_->apply(cloud);
  } catch (const CloudTooLarge& e) {
    throw ApiError(413, in_their_words(e) + " per upload");
  } catch (const Error& e) {
    throw bad_request(in_their_words(e));
  }
  memory.shrink_to(resident_bytes(cloud));

  // The oldest uploads go until this one fits: in count and in points kept. A search under way
  // keeps its own reference to its cloud.
  std::lock_guard<std::mutex> lock(mutex_);
  const auto is_upload = [](const Scene& s) { return s.source == "upload"; };
  const auto over = [&] {
    std::size_t count = 0, kept = cloud.size();
    for (const Scene& s : scenes_) {
      if (!is_upload(s)) continue;
      ++count;
      kept += s.cloud->size();
    }
    return count > 0 && ((limits_.max_uploads > 0 && count >= limits_.max_uploads) ||
                         kept > limits_.max_kept_points);
  };
  while (over()) {
    const auto oldest = std::find_if(scenes_.begin(), scenes_.end(), is_upload);
    for (auto f = footprints_.begin(); f != footprints_.end();) {
      f = f->first.rfind(oldest->id + "|", 0) == 0 ? footprints_.erase(f) : std::next(f);
    }
    scenes_.erase(oldest);
  }
  return insert(name, "upload", std::move(cloud), std::move(memory));
}

std::size_t SceneStore::search_footprint(const Scene& scene, const SceneSettings& settings) {
  FindSettings find;
  find.scene = settings;
  const std::string key = scene.id + "|" + lmk::detail::find_settings_to_json(find)["scene"].dump();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto known = footprints_.find(key);
    if (known != footprints_.end()) return known->second;
  }
  // Outside the lock: a pass over the scene's points, stopped once over the whole budget.
  const SceneFootprint f = estimate_scene_footprint(*scene.cloud, settings, budget_.budget());
  if (f.over_limit) {
    throw ApiError(413, "searching scene " + scene.id + " (" + printable(scene.name, kEchoedBytes) +
                            ", " + std::to_string(f.points) + " points over " +
                            std::to_string(f.coarse_voxels) + " coarse voxels) needs over " +
                            describe_bytes(f.bytes) +
                            ", more than the server's whole memory budget of " +
                            describe_bytes(budget_.budget()) +
                            " (lmk serve --memory-budget); crop it (work_volume) or use a "
                            "coarser leaf");
  }
  std::lock_guard<std::mutex> lock(mutex_);
  if (footprints_.size() >= kMaxFootprints) footprints_.clear();
  footprints_[key] = f.bytes;
  return f.bytes;
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
