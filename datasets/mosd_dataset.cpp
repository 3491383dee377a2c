// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/datasets/mosd_dataset.h"

#include <filesystem>
#include <map>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/random.h"
#include "lmk/landmark/landmark_file.h"

namespace lmk {

namespace fs = std::filesystem;

namespace {

// The parts of the learn set, by frame number (mOSD's README).
std::string setting_of(int frame) {
  if (frame <= 16) return "boxes";
  if (frame <= 24) return "stacked";
  if (frame <= 32) return "occluded";
  return "cylindric";
}

// A rigid motion of a camera-frame cloud: a turn about the sensor's up axis (-y) and a tilt, about
// the cloud's centre, then a shift.
Eigen::Isometry3d random_motion(SplitMix64& rng, const Eigen::Vector3d& centre) {
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * rng.uniform01(); };
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(uniform(-M_PI, M_PI), -Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(uniform(-0.35, 0.35), Eigen::Vector3d::UnitX()) *
                             Eigen::AngleAxisd(uniform(-0.35, 0.35), Eigen::Vector3d::UnitZ()))
                                .toRotationMatrix();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  const Eigen::Vector3d shift(uniform(-0.3, 0.3), uniform(-0.3, 0.3), uniform(-0.3, 0.3));
  T.translation() = centre - R * centre + shift;
  return T;
}

}  // namespace

Dataset generate_mosd_dataset(const std::string& mosd_dir, const std::string& out_dir,
                              const MosdOptions& options) {
  if (options.copies < 1) throw Error("--copies must be at least 1");
  std::map<int, fs::path> frames;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(mosd_dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("learn", 0) != 0 || entry.path().extension() != ".pcd") continue;
    const std::string number = name.substr(5, name.size() - 9);
    if (number.empty() || number.find_first_not_of("0123456789") != std::string::npos) continue;
    frames[std::stoi(number)] = entry.path();
  }
  if (ec || frames.empty())
    throw Error(mosd_dir + ": no learnN.pcd frames (expected ../shared/data/mosd/learn)");
  if (options.max_frames > 0 && frames.size() > static_cast<std::size_t>(options.max_frames)) {
    frames.erase(std::next(frames.begin(), options.max_frames), frames.end());
  }
  fs::create_directories(fs::path(out_dir) / "landmarks", ec);
  fs::create_directories(fs::path(out_dir) / "scenes", ec);
  if (ec) throw Error(out_dir + ": cannot create the dataset directory (" + ec.message() + ")");

  Dataset dataset;
  dataset.name = "mosd-learn";
  SplitMix64 rng(options.seed);
  std::size_t done = 0;
  for (const auto& [number, path] : frames) {
    const PointCloud frame = read_cloud(path.string());
    if (!frame.has_labels()) throw Error(path.string() + ": has no label field");
    // Each labelled object's points, and its box: bounds plus the margin on every side.
    std::map<std::int32_t, Eigen::AlignedBox3f> bounds;
    std::map<std::int32_t, std::size_t> counts;
    for (std::size_t i = 0; i < frame.size(); ++i) {
      if (frame.labels[i] < 2 || !is_finite(frame.points[i])) continue;
      bounds[frame.labels[i]].extend(frame.points[i]);
      ++counts[frame.labels[i]];
    }
    std::vector<std::pair<std::string, Box>> captured;
    for (const auto& [label, box] : bounds) {
      if (counts[label] < options.min_points) continue;
      const Eigen::Vector3d size =
          box.sizes().cast<double>() + Eigen::Vector3d::Constant(2.0 * options.margin);
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.translation() = box.center().cast<double>();
      const std::string name = "learn" + std::to_string(number) + "-" + std::to_string(label);
      try {
        const Landmark landmark = capture(frame, Box(pose, size), name);
        const std::string file = "landmarks/" + name + ".lmk";
        save_landmark((fs::path(out_dir) / file).string(), landmark);
        dataset.landmarks.push_back({name, file, {}});
        captured.emplace_back(name, landmark.box);
      } catch (const Error&) {
        // A flat or straight object (a box seen face-on) cannot fix a pose: no landmark of it.
      }
    }
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    std::size_t finite = 0;
    for (const auto& p : frame.points) {
      if (is_finite(p)) centre += p.cast<double>(), ++finite;
    }
    centre /= static_cast<double>(std::max<std::size_t>(finite, 1));
    for (int k = 0; k < options.copies; ++k) {
      const Eigen::Isometry3d T = random_motion(rng, centre);
      DatasetScene scene;
      scene.name = "learn" + std::to_string(number) + "-copy" + std::to_string(k);
      scene.file = "scenes/" + scene.name + ".pcd";
      scene.setting = setting_of(number);
      const PointCloud moved = frame.transformed(T);
      scene.T_scene_sensor = moved.T_cloud_sensor;
      for (const auto& [name, box] : captured)
        scene.pairs.push_back({name, true, {T * box.pose}, {}, std::nullopt});
      write_cloud((fs::path(out_dir) / scene.file).string(), moved);
      dataset.scenes.push_back(scene);
    }
    if (options.progress) options.progress(++done, frames.size());
  }
  save_dataset(out_dir, dataset);
  return dataset;
}

}  // namespace lmk
