// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/datasets/rgbd_sequence.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "lmk/geometry/error.h"
#include "lmk/geometry/input_file.h"
#include "lmk/geometry/pose.h"
#include "lmk/json/json_reader.h"

namespace lmk {
namespace {

namespace fs = std::filesystem;

// The whitespace-separated numbers of `text`, for messages naming `where`.
std::vector<double> numbers_of(const std::string& text, const std::string& where) {
  std::istringstream in(text);
  std::vector<double> out;
  for (std::string word; in >> word;) {
    char* end = nullptr;
    const double v = std::strtod(word.c_str(), &end);
    if (end == word.c_str() || *end != '\0') {
      throw Error(where + ": '" + word + "' is not a number");
    }
    out.push_back(v);
  }
  return out;
}

// A rotation and translation as read, checked to be a rigid motion (the rotation orthonormal to
// 1e-2, as trackers write them in a few digits) and made exactly orthonormal.
Eigen::Isometry3d rigid_motion(const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                               const std::string& where) {
  if (!R.allFinite() || !t.allFinite()) throw Error(where + ": the pose is not finite");
  check_translation(t, where);
  if (!(R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-2) || R.determinant() < 0.9) {
    throw Error(where + ": the pose's rotation is not a rotation (not orthonormal, or a mirror)");
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(R).normalized().toRotationMatrix();
  T.translation() = t;
  return T;
}

Eigen::Isometry3d read_pose_matrix(const std::string& path) {
  const std::vector<double> v = numbers_of(read_input_file(path, kTextInput), path);
  if (v.size() != 16) {
    throw Error(path + ": " + std::to_string(v.size()) +
                " numbers; a pose is a 4 x 4 camera-to-world matrix");
  }
  Eigen::Matrix4d M;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) M(r, c) = v[static_cast<std::size_t>(4 * r + c)];
  if (!M.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1), 1e-6)) {
    throw Error(path + ": the last row of a pose must be 0 0 0 1");
  }
  return rigid_motion(M.topLeftCorner<3, 3>(), M.topRightCorner<3, 1>(), path);
}

std::optional<std::string> first_existing(const fs::path& dir,
                                          std::initializer_list<const char*> names) {
  for (const char* n : names) {
    if (fs::is_regular_file(dir / n)) return (dir / n).string();
  }
  return std::nullopt;
}

PinholeIntrinsics intrinsics_for(const fs::path& dir, const RgbdReadOptions& options,
                                 const char* hint) {
  if (options.intrinsics) {
    options.intrinsics->validate("--intrinsics");
    return *options.intrinsics;
  }
  if (const auto file =
          first_existing(dir, {"camera-intrinsics.txt", "intrinsics.K.txt", "intrinsics.txt"})) {
    return read_intrinsics(*file);
  }
  throw Error(dir.string() +
              ": no intrinsics (camera-intrinsics.txt, intrinsics.K.txt or intrinsics.txt); give "
              "them with --intrinsics FX FY CX CY" +
              hint);
}

// 7-Scenes, and 3DMatch's frame triples.
RgbdSequence read_frames(const fs::path& dir, const RgbdReadOptions& options) {
  std::vector<std::string> depth_files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    const std::string suffix = ".depth.png";
    if (name.size() > suffix.size() &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) {
      depth_files.push_back(entry.path().string());
    }
  }
  std::sort(depth_files.begin(), depth_files.end());
  RgbdSequence sequence;
  sequence.layout = "frames";
  if (depth_files.empty()) return sequence;  // no layout lmk knows: the caller says so
  const PinholeIntrinsics k = intrinsics_for(dir, options, " (7-Scenes: 585 585 320 240)");
  const bool colour = options.colour_registered.value_or(false);
  for (const std::string& depth : depth_files) {
    const std::string stem = depth.substr(0, depth.size() - std::string(".depth.png").size());
    RgbdFrame frame;
    frame.name = fs::path(stem).filename().string();
    frame.depth_file = depth;
    frame.intrinsics = k;
    frame.metres_per_unit = 0.001;
    const std::string pose = stem + ".pose.txt";
    if (!fs::is_regular_file(pose))
      throw Error(pose + ": missing (every depth frame needs a pose)");
    frame.T_world_camera = read_pose_matrix(pose);
    if (colour && fs::is_regular_file(stem + ".color.png")) frame.colour_file = stem + ".color.png";
    sequence.frames.push_back(std::move(frame));
  }
  return sequence;
}

// A TUM list: "timestamp value..." lines, '#' comments.
std::vector<std::vector<std::string>> tum_lines(const std::string& path) {
  std::istringstream in(read_input_file(path, kTextInput));
  std::vector<std::vector<std::string>> out;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string x; words >> x;) w.push_back(x);
    if (!w.empty()) out.push_back(std::move(w));
  }
  return out;
}

double tum_time(const std::string& word, const std::string& where) {
  const std::vector<double> v = numbers_of(word, where);
  if (v.size() != 1 || !std::isfinite(v[0]))
    throw Error(where + ": a bad timestamp '" + word + "'");
  return v[0];
}

// The entry of `times` (sorted) nearest to t, if within max_dt.
template <class T>
const T* nearest_in_time(const std::vector<std::pair<double, T>>& items, double t, double max_dt) {
  const auto it =
      std::lower_bound(items.begin(), items.end(), t,
                       [](const std::pair<double, T>& a, double x) { return a.first < x; });
  const std::pair<double, T>* best = nullptr;
  if (it != items.end()) best = &*it;
  if (it != items.begin() && (!best || t - std::prev(it)->first < best->first - t)) {
    best = &*std::prev(it);
  }
  if (!best || std::abs(best->first - t) > max_dt) return nullptr;
  return &best->second;
}

// Throws lmk::Error unless `name`, as `list` gives it, names a file inside `dir` after every
// symbolic link: a sequence's lists may not reach files elsewhere ("../../etc/passwd").
void check_inside_sequence(const fs::path& dir, const std::string& name, const std::string& list) {
  std::error_code ec;
  if (!lies_within(dir / name, dir, ec)) {
    throw Error((dir / "").string() + ": " + list + " names '" + printable(name, kEchoedBytes) +
                "', outside the sequence's directory");
  }
}

// groundtruth.txt's camera poses, in time order.
std::vector<std::pair<double, Eigen::Isometry3d>> tum_poses(const std::string& gt_path) {
  std::vector<std::pair<double, Eigen::Isometry3d>> poses;
  for (const auto& w : tum_lines(gt_path)) {
    if (w.size() != 8) throw Error(gt_path + ": a line needs 8 values: t tx ty tz qx qy qz qw");
    const std::vector<double> v = numbers_of(
        w[1] + " " + w[2] + " " + w[3] + " " + w[4] + " " + w[5] + " " + w[6] + " " + w[7],
        gt_path);
    const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
    if (!(std::abs(q.norm() - 1.0) < 1e-2)) {
      throw Error(gt_path + ": the quaternion at t = " + w[0] + " is not of unit length");
    }
    poses.emplace_back(tum_time(w[0], gt_path), rigid_motion(q.normalized().toRotationMatrix(),
                                                             {v[0], v[1], v[2]}, gt_path));
  }
  std::sort(poses.begin(), poses.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  return poses;
}

// A frame a TUM sequence lists: its depth time, depth file and colour file.
struct TumEntry {
  double t;
  std::string depth, colour;
};

// The frames from associations.txt, or depth.txt with rgb.txt; `list` names the file that named
// them. Each listed file must lie inside the sequence, as dataset.json's must, and each frame be
// listed once: a repeated line became two frames of one name, and the writer then blamed its
// output (#47).
std::vector<TumEntry> tum_entries(const fs::path& dir, const RgbdReadOptions& options) {
  std::vector<TumEntry> entries;
  std::string list = "depth.txt";
  if (const auto assoc = first_existing(dir, {"associations.txt", "associate.txt"})) {
    list = fs::path(*assoc).filename().string();
    for (const auto& w : tum_lines(*assoc)) {
      if (w.size() != 4) throw Error(*assoc + ": a line needs 4 values: t file t file");
      const bool depth_first = w[1].find("depth") != std::string::npos;
      const std::size_t d = depth_first ? 0 : 2, c = depth_first ? 2 : 0;
      entries.push_back({tum_time(w[d], *assoc), w[d + 1], w[c + 1]});
    }
  } else {
    const std::string depth_list = (dir / "depth.txt").string();
    std::vector<std::pair<double, std::string>> colours;
    if (fs::is_regular_file(dir / "rgb.txt")) {
      for (const auto& w : tum_lines((dir / "rgb.txt").string()))
        if (w.size() >= 2) colours.emplace_back(tum_time(w[0], "rgb.txt"), w[1]);
      std::sort(colours.begin(), colours.end());
    }
    for (const auto& w : tum_lines(depth_list)) {
      if (w.size() != 2) throw Error(depth_list + ": a line needs 2 values: timestamp file");
      const double t = tum_time(w[0], depth_list);
      const std::string* colour = nearest_in_time(colours, t, options.max_time_difference);
      entries.push_back({t, w[1], colour ? *colour : std::string()});
    }
  }
  std::set<double> listed;
  for (const TumEntry& e : entries) {
    check_inside_sequence(dir, e.depth, list);
    if (!e.colour.empty()) check_inside_sequence(dir, e.colour, list);
    if (!listed.insert(e.t).second) {
      throw Error((dir / "").string() + ": " + list +
                  " lists the frame at t = " + std::to_string(e.t) + " twice");
    }
  }
  return entries;
}

RgbdSequence read_tum(const fs::path& dir, const RgbdReadOptions& options) {
  const PinholeIntrinsics k =
      intrinsics_for(dir, options,
                     " (TUM ships none: freiburg1 517.3 516.5 318.6 255.3, freiburg2 520.9 521.0 "
                     "325.1 249.7, freiburg3 535.4 539.2 320.1 247.6)");
  const std::string gt_path = (dir / "groundtruth.txt").string();
  const std::vector<std::pair<double, Eigen::Isometry3d>> poses = tum_poses(gt_path);
  const std::vector<TumEntry> entries = tum_entries(dir, options);
  const bool colour = options.colour_registered.value_or(true);
  RgbdSequence sequence;
  sequence.layout = "tum";
  for (const TumEntry& e : entries) {
    const Eigen::Isometry3d* pose = nearest_in_time(poses, e.t, options.max_time_difference);
    if (!pose) continue;  // outside the motion capture's coverage: TUM's usual gaps
    RgbdFrame frame;
    std::ostringstream name;
    name.precision(6);
    name << std::fixed << e.t;
    frame.name = name.str();
    frame.depth_file = (dir / e.depth).string();
    if (colour && !e.colour.empty()) frame.colour_file = (dir / e.colour).string();
    frame.intrinsics = k;
    frame.metres_per_unit = 1.0 / 5000.0;  // TUM's depth factor
    frame.T_world_camera = *pose;
    sequence.frames.push_back(std::move(frame));
  }
  if (sequence.frames.empty()) {
    throw Error(gt_path + ": no depth frame has a pose within " +
                std::to_string(options.max_time_difference) + " s");
  }
  return sequence;
}

RgbdSequence read_bop(const fs::path& dir, const RgbdReadOptions& options) {
  const std::string path = (dir / "scene_camera.json").string();
  const detail::JsonReader r(path);
  const nlohmann::json j = r.parse(read_input_file(path, kJsonInput));
  if (!j.is_object() || j.empty()) r.fail("", "must be an object of image ids");
  std::vector<std::pair<long, std::string>> ids;
  for (const auto& item : j.items()) {
    char* end = nullptr;
    const long id = std::strtol(item.key().c_str(), &end, 10);
    if (end == item.key().c_str() || *end != '\0' || id < 0)
      r.fail("", "'" + item.key() + "' is not an image id");
    ids.emplace_back(id, item.key());
  }
  std::sort(ids.begin(), ids.end());
  const bool colour = options.colour_registered.value_or(true);
  RgbdSequence sequence;
  sequence.layout = "bop";
  for (const auto& [id, key] : ids) {
    const nlohmann::json& c = j.at(key);
    const std::string where = path + ": " + key;
    if (!c.contains("cam_R_w2c") || !c.contains("cam_t_w2c")) {
      r.fail(key, "no cam_R_w2c / cam_t_w2c: lmk needs the camera's pose in every frame");
    }
    const Eigen::VectorXd K = r.numbers(r.field(c, key, "cam_K"), key + ".cam_K", 9);
    const Eigen::VectorXd R = r.numbers(c.at("cam_R_w2c"), key + ".cam_R_w2c", 9);
    const Eigen::VectorXd t = r.numbers(c.at("cam_t_w2c"), key + ".cam_t_w2c", 3);
    const nlohmann::json scale = c.value("depth_scale", nlohmann::json(1.0));
    if (!scale.is_number() || !(scale.get<double>() > 0.0) || !std::isfinite(scale.get<double>()))
      r.fail(key + ".depth_scale", "must be a positive number");
    const double depth_scale = scale.get<double>();
    Eigen::Matrix3d R_cw;
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 3; ++col) R_cw(row, col) = R[3 * row + col];
    const Eigen::Isometry3d T_camera_world =
        rigid_motion(R_cw, Eigen::Vector3d(t[0], t[1], t[2]) * 1e-3, where);  // BOP's mm
    char file[32];
    std::snprintf(file, sizeof(file), "%06ld.png", id);
    RgbdFrame frame;
    frame.name = key;
    frame.depth_file = (dir / "depth" / file).string();
    if (colour && fs::is_regular_file(dir / "rgb" / file))
      frame.colour_file = (dir / "rgb" / file).string();
    frame.intrinsics =
        options.intrinsics.value_or(intrinsics_from_camera_matrix(K.data(), where + ".cam_K"));
    frame.intrinsics.validate(where + ".cam_K");
    frame.metres_per_unit = depth_scale * 1e-3;  // depth_scale x value = mm
    frame.T_world_camera = T_camera_world.inverse();
    sequence.frames.push_back(std::move(frame));
  }
  return sequence;
}

}  // namespace

RgbdSequence read_rgbd_sequence(const std::string& dir_text, const RgbdReadOptions& options) {
  const fs::path dir(dir_text);
  if (!fs::is_directory(dir)) throw Error(dir_text + ": not a directory");
  RgbdSequence sequence;
  if (fs::is_regular_file(dir / "scene_camera.json")) {
    sequence = read_bop(dir, options);
  } else if (fs::is_regular_file(dir / "groundtruth.txt")) {
    sequence = read_tum(dir, options);
  } else {
    sequence = read_frames(dir, options);
  }
  if (sequence.frames.empty()) {
    throw Error(dir_text +
                ": no RGB-D frames (frame-NNNNNN.depth.png with .pose.txt, TUM's groundtruth.txt "
                "and depth.txt, or BOP's scene_camera.json)");
  }
  return sequence;
}

PointCloud load_rgbd_frame(const RgbdFrame& frame) {
  const DepthImage depth = read_depth_image(frame.depth_file);
  DepthToCloud conversion;
  conversion.metres_per_unit = frame.metres_per_unit;
  if (frame.colour_file.empty()) return depth_to_cloud(depth, frame.intrinsics, conversion);
  const ColourImage colour = read_colour_image(frame.colour_file);
  return depth_to_cloud(depth, frame.intrinsics, conversion, &colour);
}

}  // namespace lmk
