// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/rgbd_dataset.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/statistics.h"
#include "lmk/json/depth_correction_json.h"
#include "lmk/json/pose_json.h"
#include "lmk/landmark/distinctiveness.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/registration/frame_registration.h"
#include "lmk/registration/icp.h"

namespace lmk {
namespace {

namespace fs = std::filesystem;

// A frame of the sequence as the dataset uses it: its cloud in its camera frame, its camera pose.
struct UsedFrame {
  const RgbdFrame* frame;
  PointCloud cloud;
  PointCloud reduced;  ///< 2 cm voxels with normals, for the registration
};

// The median depth of the frames' returns, for the default box side.
double median_depth(const std::vector<UsedFrame>& frames) {
  std::vector<double> z;
  for (const UsedFrame& f : frames)
    for (const auto& p : f.reduced.points) z.push_back(p.z());
  const std::optional<double> m = median(std::move(z));
  if (!m) throw Error("the sequence's frames hold no depth return");
  return *m;
}

// The whole-frame registration of frame a onto frame b, started from the camera poses
// (T_b_a): point-to-plane ICP of a's 2 cm points against b's, correspondences within 5 cm, a Huber
// loss at 1 cm. Its answer is what the pair's ground truth is checked against.
IcpResult register_frames(const UsedFrame& a, const UsedFrame& b, const Eigen::Isometry3d& T_b_a) {
  return register_frames(a.reduced, b.reduced, T_b_a);
}

// The fraction of `points` (frame a) that frame b does not see where the poses put them: outside
// its image, without a return there, or farther than `tolerance` plus the depth noise from b's
// measured depth (behind a nearer surface, or where b saw through).
double hidden_in(const std::vector<Eigen::Vector3f>& points, const Eigen::Isometry3d& T_b_a,
                 const UsedFrame& b) {
  if (points.empty()) return 1.0;
  const PinholeIntrinsics& k = b.frame->intrinsics;
  std::size_t seen = 0;
  for (const auto& p : points) {
    const Eigen::Vector3d q = T_b_a * p.cast<double>();
    const std::optional<std::size_t> pixel =
        k.pixel_of(q, static_cast<int>(b.cloud.width), static_cast<int>(b.cloud.height));
    if (!pixel) continue;
    const Eigen::Vector3f& m = b.cloud.points[*pixel];
    // 1.5 cm, the protocol's spirit for a seen point, plus the Kinect-like noise at that depth.
    const double tolerance = 0.015 + 0.0057 * q.z() * q.z();
    if (is_finite(m) && std::abs(m.z() - q.z()) < tolerance) ++seen;
  }
  return 1.0 - static_cast<double>(seen) / static_cast<double>(points.size());
}

// Why the capture refused a box, in a few words for the import's tally.
std::string refusal_reason(const std::string& message) {
  for (const char* word : {"flat", "straight", "too few", "no scene point"}) {
    if (message.find(word) != std::string::npos) return word;
  }
  return message;
}

// The depth error fitted on the frames the dataset does not use, so that no frame it measures on
// shaped the correction.
DepthCalibration calibrate_on_unused_frames(const RgbdSequence& sequence,
                                            const RgbdDatasetOptions& options) {
  std::vector<PointCloud> clouds;
  std::vector<Eigen::Isometry3d> poses;
  for (std::size_t i = 0; i < sequence.frames.size(); ++i) {
    if (i % options.frame_stride == 0) continue;
    clouds.push_back(load_rgbd_frame(sequence.frames[i]));
    poses.push_back(sequence.frames[i].T_world_camera);
  }
  if (clouds.empty()) {
    throw Error(
        "from-rgbd: --calibrate-depth needs frames the dataset does not use (a frame "
        "stride above 1)");
  }
  std::vector<const PointCloud*> views;
  for (const PointCloud& c : clouds) views.push_back(&c);
  return fit_depth_correction(views, poses, sequence.frames.front().intrinsics,
                              options.calibration);
}

}  // namespace

RgbdImport generate_rgbd_dataset(const std::string& sequence_dir, const std::string& out_dir,
                                 const RgbdDatasetOptions& options) {
  if (options.frame_stride == 0 || options.min_gap > options.max_gap)
    throw Error("from-rgbd: the frame stride must be positive and min_gap at most max_gap");
  if (options.calibrate_depth && options.depth_correction)
    throw Error("from-rgbd: either fit the depth correction or give one, not both");
  const RgbdSequence sequence = read_rgbd_sequence(sequence_dir, options.read);
  RgbdImport import;
  import.layout = sequence.layout;
  Dataset& dataset = import.dataset;
  dataset.name = options.name.empty()
                     ? fs::path(sequence_dir).lexically_normal().filename().string()
                     : options.name;
  if (dataset.name.empty() || dataset.name == ".")
    dataset.name = fs::absolute(sequence_dir).lexically_normal().parent_path().filename().string();
  std::error_code ec;
  fs::create_directories(fs::path(out_dir) / "landmarks", ec);
  fs::create_directories(fs::path(out_dir) / "scenes", ec);
  if (ec) throw Error(out_dir + ": cannot create the dataset directory (" + ec.message() + ")");

  std::vector<UsedFrame> frames;
  for (std::size_t i = 0; i < sequence.frames.size(); i += options.frame_stride) {
    frames.push_back({&sequence.frames[i], load_rgbd_frame(sequence.frames[i]), {}});
  }
  if (options.calibrate_depth)
    import.depth_calibration = calibrate_on_unused_frames(sequence, options);
  if (options.depth_correction) import.depth_calibration = options.depth_correction;
  if (import.depth_calibration) {
    for (UsedFrame& f : frames) import.depth_calibration->correction.apply(f.cloud);
  }
  for (UsedFrame& f : frames) {
    f.reduced = reduce_for_registration(f.cloud);
  }
  import.box_side = options.box_side.value_or(std::clamp(0.15 * median_depth(frames), 0.08, 0.40));
  UserBoxRule rule;
  rule.box_side = import.box_side;
  rule.max_boxes = options.boxes_per_frame;

  // Landmarks: the rule's boxes in every frame used, captured and checked as `lmk capture` does.
  struct Captured {
    std::size_t frame;
    std::string name;
    Landmark landmark;
  };
  std::vector<Captured> captured;
  nlohmann::json refusals = nlohmann::json::array();
  const std::size_t steps = 2 * frames.size();
  CaptureSettings capture_settings;
  capture_settings.depth_smoothing = options.depth_smoothing;
  FindSettings check_settings;
  check_settings.scene.depth_smoothing = options.depth_smoothing;
  std::size_t done = 0;
  for (std::size_t a = 0; a < frames.size(); ++a) {
    const std::vector<Box> boxes =
        user_like_boxes(frames[a].cloud, frames[a].frame->intrinsics, rule);
    for (std::size_t k = 0; k < boxes.size(); ++k) {
      ++import.boxes;
      const std::string name = frames[a].frame->name + "-" + std::to_string(k);
      std::string why;
      try {
        Landmark landmark = capture(frames[a].cloud, boxes[k], name, capture_settings);
        const DistinctivenessReport check =
            check_distinctiveness(frames[a].cloud, landmark, check_settings);
        if (!check.found_itself) {
          why = "not found in its own frame";
        } else if (!check.other_instances.empty()) {
          why = "matches elsewhere in its own frame";
        } else {
          captured.push_back({a, name, std::move(landmark)});
        }
      } catch (const Error& e) {
        why = refusal_reason(e.what());
      }
      if (!why.empty()) {
        ++import.refused[why];
        refusals.push_back(
            {{"landmark", name}, {"reason", why}, {"box", detail::pose_to_json(boxes[k].pose)}});
      }
    }
    if (options.progress) options.progress(++done, steps);
  }
  for (const Captured& c : captured) {
    const std::string file = "landmarks/" + c.name + ".lmk";
    save_landmark((fs::path(out_dir) / file).string(), c.landmark);
    dataset.landmarks.push_back({c.name, file, {}});
  }

  // Scenes: every frame used, with each landmark cut min_gap to max_gap frames away from it.
  nlohmann::json checks = nlohmann::json::array();
  for (std::size_t b = 0; b < frames.size(); ++b) {
    DatasetScene scene;
    scene.name = frames[b].frame->name;
    scene.file = "scenes/" + scene.name + ".pcd";
    scene.setting = dataset.name;
    std::map<std::size_t, IcpResult> registrations;  // by capture frame
    for (const Captured& c : captured) {
      const std::size_t gap = options.frame_stride * (b > c.frame ? b - c.frame : c.frame - b);
      if (gap < options.min_gap || gap > options.max_gap) continue;
      const Eigen::Isometry3d T_b_a =
          frames[b].frame->T_world_camera.inverse() * frames[c.frame].frame->T_world_camera;
      auto it = registrations.find(c.frame);
      if (it == registrations.end())
        it = registrations.emplace(c.frame, register_frames(frames[c.frame], frames[b], T_b_a))
                 .first;
      const IcpResult& reg = it->second;
      const Eigen::Vector3d centre = c.landmark.box.center();
      DatasetPair pair;
      pair.landmark = c.name;
      pair.in_context = true;
      pair.instances = {T_b_a * c.landmark.box.pose};
      pair.hidden = {hidden_in(c.landmark.points.points, T_b_a, frames[b])};
      pair.pose_check =
          PoseCheck{(reg.T_target_source * centre - T_b_a * centre).norm(),
                    rotation_angle_between(reg.T_target_source.linear(), T_b_a.linear())};
      const bool trusted = pair.pose_check->translation <= options.max_pose_disagreement &&
                           pair.pose_check->rotation <= options.max_pose_rotation_disagreement;
      checks.push_back({{"scene", scene.name},
                        {"landmark", c.name},
                        {"frames_apart", gap},
                        {"disagreement_m", pair.pose_check->translation},
                        {"disagreement_rad", pair.pose_check->rotation},
                        {"registration_inliers", reg.inliers},
                        {"registration_residual_m", reg.final_error},
                        {"kept", trusted}});
      if (!trusted) {
        ++import.pairs_left_out;
        continue;
      }
      ++import.pairs;
      scene.pairs.push_back(std::move(pair));
    }
    if (!scene.pairs.empty()) {
      write_cloud((fs::path(out_dir) / scene.file).string(), frames[b].cloud);
      dataset.scenes.push_back(std::move(scene));
    }
    if (options.progress) options.progress(++done, steps);
  }
  save_dataset(out_dir, dataset);

  nlohmann::json record = {
      {"format", "lmk-rgbd-import"},
      {"version", 1},
      {"sequence", fs::path(sequence_dir).lexically_normal().string()},
      {"layout", sequence.layout},
      {"frames_in_sequence", sequence.frames.size()},
      {"frame_stride", options.frame_stride},
      {"gap_frames", {options.min_gap, options.max_gap}},
      {"rule",
       {{"box_side_m", rule.box_side},
        {"voxels_per_side", rule.voxels_per_side},
        {"depth_m", {rule.min_depth, rule.max_depth}},
        {"min_cell_points", rule.min_cell_points},
        {"off_plane_angle_rad", rule.off_plane_angle},
        {"min_off_plane", rule.min_off_plane},
        {"max_boxes", rule.max_boxes}}},
      {"boxes", import.boxes},
      {"depth_smoothing_px", options.depth_smoothing},
      {"depth_correction", import.depth_calibration
                               ? detail::depth_calibration_to_json(*import.depth_calibration)
                               : nlohmann::json(nullptr)},
      {"landmarks", captured.size()},
      {"refused", refusals},
      {"pose_bound",
       {{"translation_m", options.max_pose_disagreement},
        {"rotation_rad", options.max_pose_rotation_disagreement}}},
      {"pairs", import.pairs},
      {"pairs_left_out", import.pairs_left_out},
      {"pose_checks", checks}};
  write_text_atomically(fs::path(out_dir) / "import.json", record.dump(1) + "\n");
  return import;
}

}  // namespace lmk
