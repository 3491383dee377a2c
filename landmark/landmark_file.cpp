// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/landmark_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/child_process.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/filters.h"
#include "lmk/geometry/input_file.h"
#include "lmk/geometry/pose.h"
#include "lmk/json/box_json.h"
#include "lmk/json/pose_json.h"
#include "lmk/json/settings_json.h"
#include "lmk/landmark/detail/landmark_container.h"
#include "lmk/landmark/detail/landmark_record.h"
#include "lmk/landmark/detail/vdb_landmark_file.h"
#include "lmk/landmark/internal/capture_findings_json.h"
#include "lmk/landmark/shape_check.h"

namespace lmk {

namespace fs = std::filesystem;

namespace {

nlohmann::json to_json(const Landmark& l) {
  nlohmann::json j = {{"format_version", l.format_version},
                      {"name", l.name},
                      {"box", detail::box_to_json(l.box)},
                      {"sensor_origin", detail::vector_to_json(l.sensor_origin)},
                      {"capture", detail::settings_to_json(l.settings)},
                      {"up", detail::vector_to_json(l.up)}};
  if (l.findings.present) j["capture_findings"] = detail::capture_findings_to_json(l.findings);
  if (l.multi_view()) {  // each point's views are points.pcd's labels
    j["view_origins"] = nlohmann::json::array();
    for (const Eigen::Vector3d& o : l.view_origins) {
      j["view_origins"].push_back(detail::vector_to_json(o));
    }
  }
  return j;
}

// A box or a landmark's view poses: a few lines. JSON grows about 12-fold as it is parsed, so a
// 255 MB box file took 3.1 GB before it was refused (issue #61, finding 5); 1 MiB holds thousands
// of poses.
constexpr InputKind kSmallJsonInput{"JSON file", std::uintmax_t{1} << 20};

nlohmann::json read_json_file(const std::string& path, const InputKind& kind = kJsonInput) {
  const std::string text = read_input_file(path, kind);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": not valid JSON (" + e.what() + ")");
  }
}

Landmark from_json(const nlohmann::json& j, const std::string& path) {
  Landmark l;
  try {
    l.format_version = j.at("format_version").get<int>();
    l.name = j.at("name").get<std::string>();
    l.box = detail::box_from_json(detail::json_field(j, "box", path), path + ": box");
    l.sensor_origin = detail::numbers_from_json(detail::json_field(j, "sensor_origin", path), 3,
                                                path + ": sensor_origin");
    // Every capture setting by its description; those an older export lacks keep their defaults.
    detail::settings_from_json(j.at("capture"), path + ": capture", l.settings);
    if (j.contains("up")) l.up = detail::numbers_from_json(j.at("up"), 3, path + ": up");
    if (j.contains("capture_findings")) {
      l.findings =
          detail::capture_findings_from_json(j.at("capture_findings"), path + ": capture_findings");
    }
    if (j.contains("view_origins")) {
      const nlohmann::json& origins = j.at("view_origins");
      if (!origins.is_array()) throw Error(path + ": view_origins must be an array");
      for (std::size_t v = 0; v < origins.size(); ++v) {
        l.view_origins.push_back(detail::numbers_from_json(
            origins[v], 3, path + ": view_origins[" + std::to_string(v) + "]"));
      }
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": " + e.what());
  }
  return l;
}

detail::LandmarkRecord record_of(const Landmark& landmark) {
  detail::LandmarkRecord r;
  r.header = to_json(landmark);
  r.points = landmark.points.points;
  r.views = landmark.point_views;
  r.colours = landmark.points.colors;
  r.empty_voxels = landmark.empty_space.voxels();
  return r;
}

// lmk::Error unless every stored empty voxel lies within the box, a voxel's diagonal to spare: the
// capture keeps only voxels inside it, and a voxel elsewhere would mean what no capture saw.
void check_empty_voxels(const detail::LandmarkRecord& r, const Landmark& l,
                        const std::string& path) {
  const double voxel = l.settings.leaf_size;
  const Eigen::Vector3d reach = 0.5 * l.box.size + Eigen::Vector3d::Constant(2.0 * voxel);
  const Eigen::Isometry3d box_from_capture = l.box.pose.inverse();
  for (const Eigen::Vector3i& v : r.empty_voxels) {
    const Eigen::Vector3d in_box = box_from_capture * (v.cast<double>() * voxel);
    if ((in_box.cwiseAbs().array() > reach.array()).any()) {
      throw Error(path + ": corrupt landmark file: an empty-space voxel lies outside the box");
    }
  }
}

// lmk::Error when an empty voxel lies within the surface margin of the landmark's points: the
// capture leaves those out (EmptySpaceGrid::observe), so such a voxel was not written by lmk. The
// rebuilt distance field is the capture's own; a thousandth of the margin allows for rounding.
void check_empty_space_off_the_surface(const Landmark& l, const std::string& path) {
  const auto surface = l.distance.sampler();
  const double margin = l.settings.empty_space_margin * (1.0 - 1e-3);
  for (const Eigen::Vector3f& centre : l.empty_space.centres()) {
    if (surface.distance(centre) < margin) {
      throw Error(path +
                  ": corrupt landmark file: an empty-space voxel lies on the landmark's "
                  "surface, where no capture marks space free");
    }
  }
}

// The landmark a record holds, its derived parts rebuilt: the distance field and the normals from
// the points, the empty space from its voxels (format 1 stored none: rays to the landmark's own
// points). What the file did not store of the capture check is measured again.
Landmark landmark_of(const detail::LandmarkRecord& r, const std::string& path) {
  Landmark l = from_json(r.header, path);
  if (l.format_version < 1 || l.format_version > kLandmarkFormatVersion) {
    throw Error(path + ": landmark format version " + std::to_string(l.format_version) +
                " is not supported (this lmk reads versions 1 to " +
                std::to_string(kLandmarkFormatVersion) + ")");
  }
  l.points.points = r.points;
  l.points.colors = r.colours;
  l.points.set_unorganized();
  l.points.T_cloud_sensor = Eigen::Isometry3d::Identity();
  l.points.T_cloud_sensor.translation() = l.sensor_origin;
  l.point_views = r.views;
  const bool stored_empty_space = l.format_version >= 2;
  l.format_version = kLandmarkFormatVersion;
  l.validate(path);  // before anything is built from it
  if (stored_empty_space) {
    check_empty_voxels(r, l, path);
    l.distance = DistanceField(l.points.points, {l.settings.leaf_size, l.settings.distance_band});
    l.empty_space = EmptySpaceGrid::from_voxels(l.settings.leaf_size, r.empty_voxels);
    check_empty_space_off_the_surface(l, path);
    estimate_landmark_normals(l);
  } else {
    prepare_landmark(l);
  }
  if (!l.findings.present) l.findings = check_shape(l, nullptr).findings;
  return l;
}

// A file of format 1 to 4, read in a child process: OpenVDB decodes its grids, and behind a valid
// checksum a forged grid can abort the process that decodes it. The child hands back the landmark
// as a format-5 record.
detail::LandmarkRecord read_old_format(const std::string& path) {
  const std::string bytes = run_in_child(
      [&path] { return detail::record_bytes(record_of(detail::read_vdb_landmark(path))); },
      path + ": corrupt landmark file");
  return detail::parse_record(path, bytes);
}

// The record in the file at `path`, whose `bytes` these are, of any format lmk has written.
detail::LandmarkRecord read_record(const std::string& path, const std::string& bytes) {
  if (detail::has_vdb_magic(bytes)) return read_old_format(path);
  if (!detail::has_record_magic(bytes)) {
    throw Error(path + ": not an lmk landmark file (neither format 5 nor an OpenVDB file)");
  }
  detail::check_landmark_trailer(path, bytes);
  return detail::parse_record(path, bytes.substr(0, bytes.size() - detail::kLandmarkTrailerSize));
}

}  // namespace

Box read_box_json(const std::string& path) {
  const nlohmann::json j = read_json_file(path, kSmallJsonInput);
  try {
    return detail::box_from_json(j, path + ": box");
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": " + e.what());
  }
}

std::vector<Eigen::Isometry3d> read_view_poses(const std::string& path) {
  const nlohmann::json j = read_json_file(path, kSmallJsonInput);
  if (!j.is_array() || j.empty()) {
    throw Error(path + ": the views' poses must be a non-empty JSON array, one pose per view");
  }
  std::vector<Eigen::Isometry3d> poses;
  for (std::size_t v = 0; v < j.size(); ++v) {
    const std::string where = path + ": pose " + std::to_string(v + 1);
    try {
      poses.push_back(detail::pose_from_json(j[v], where));
    } catch (const nlohmann::json::exception& e) {
      throw Error(where + ": " + e.what());
    }
    if (!is_valid_pose(poses.back())) {
      throw Error(where + ": not a finite rigid motion with a unit quaternion");
    }
  }
  return poses;
}

int landmark_file_version(const std::string& path) {
  const std::string bytes = read_input_file(path, kLandmarkInput);
  if (detail::has_vdb_magic(bytes)) {
    const std::string version =
        run_in_child([&path] { return std::to_string(detail::read_vdb_landmark_version(path)); },
                     path + ": corrupt landmark file");
    return std::stoi(version);
  }
  read_record(path, bytes);  // checked as load_landmark() checks it
  return kLandmarkFormatVersion;
}

void save_landmark(const std::string& path, const Landmark& landmark) {
  landmark.validate("save " + path);
  Landmark stored = landmark;
  stored.format_version = kLandmarkFormatVersion;
  const std::string data = detail::record_bytes(record_of(stored));
  write_file_atomically(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << data << detail::landmark_trailer(data);
    if (!out) throw Error(path + ": write failed");
  });
}

Landmark load_landmark(const std::string& path) {
  return landmark_of(read_record(path, read_input_file(path, kLandmarkInput)), path);
}

int upgrade_landmark_file(const std::string& path) {
  const std::string bytes = read_input_file(path, kLandmarkInput);
  if (!detail::has_vdb_magic(bytes)) {
    read_record(path, bytes);  // checked as load_landmark() checks it
    return kLandmarkFormatVersion;
  }
  // An old file's grids decoded once, in one child: the record it hands back keeps the version
  // the file was written in.
  const detail::LandmarkRecord record = read_old_format(path);
  save_landmark(path, landmark_of(record, path));
  return record.header.at("format_version").get<int>();
}

void export_landmark(const Landmark& landmark, const std::string& out_dir) {
  landmark.validate("export " + landmark.name);
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (!fs::is_directory(out_dir)) throw Error(out_dir + ": cannot create the directory");
  PointCloud points = landmark.points;
  if (landmark.multi_view()) {
    points.labels.assign(landmark.point_views.begin(), landmark.point_views.end());
  }
  write_cloud((fs::path(out_dir) / "points.pcd").string(), points, {Encoding::kBinary});
  const std::string json_path = (fs::path(out_dir) / "landmark.json").string();
  write_file_atomically(json_path, [&](const fs::path& tmp) {
    std::ofstream out(tmp);
    out << to_json(landmark).dump(2) << "\n";
    if (!out) throw Error(json_path + ": write failed");
  });
}

Landmark import_landmark(const std::string& dir) {
  const std::string json_path = (fs::path(dir) / "landmark.json").string();
  if (!fs::exists(json_path)) {
    throw Error(json_path + ": no such file (import expects landmark.json and points.pcd)");
  }
  const nlohmann::json j = read_json_file(json_path);
  Landmark landmark = from_json(j, json_path);
  // Its settings before its points are read or anything is built from them (issue #47).
  check_capture_settings(landmark.settings, json_path);
  landmark.points = remove_non_finite(read_cloud((fs::path(dir) / "points.pcd").string()));
  if (landmark.multi_view()) {  // each point's views are its label
    if (!landmark.points.has_labels()) {
      throw Error(dir + ": points.pcd has no labels for the views of a landmark of several views");
    }
    landmark.point_views.assign(landmark.points.labels.begin(), landmark.points.labels.end());
  }
  landmark.points.labels.clear();
  landmark.points.T_cloud_sensor = Eigen::Isometry3d::Identity();
  landmark.points.T_cloud_sensor.translation() = landmark.sensor_origin;
  // Upgrade: versions 1 and 2 are one view.
  if (landmark.format_version < kLandmarkFormatVersion && landmark.format_version >= 1) {
    landmark.format_version = kLandmarkFormatVersion;
  }
  landmark.validate(dir);
  prepare_landmark(landmark);  // the capture scene is not exported: rays to its own points only
  // An export from before format 4 gains what can be measured without the capture scene.
  if (!landmark.findings.present) landmark.findings = check_shape(landmark, nullptr).findings;
  return landmark;
}

}  // namespace lmk
