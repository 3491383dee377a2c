// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/datasets/rgbd_dataset.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <variant>

#include "lmk/datasets/track_sequences.h"
#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/statistics.h"
#include "lmk/json/depth_correction_json.h"
#include "lmk/json/pose_json.h"
#include "lmk/landmark/capture_views.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/occupancy/tsdf_volume.h"
#include "lmk/registration/frame_registration.h"
#include "lmk/registration/icp.h"
#include "lmk/search/capture_check.h"

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
  if (message.find("first view") != std::string::npos) return "a view did not register";
  if (message.find("has no point inside the box") != std::string::npos) {
    return "a view without a point in the box";
  }
  return message;
}

// The used frames that give a box cut in frame `a` its further views, nearest first and after
// before: a + step, a - step, a + 2 step, ... (step = the view gap in used frames), as many as
// exist up to `count`.
std::vector<std::size_t> further_views(std::size_t a, std::size_t frames, std::size_t step,
                                       std::size_t count) {
  std::vector<std::size_t> out;
  for (std::size_t k = 1; out.size() < count && (a + k * step < frames || k * step <= a); ++k) {
    if (a + k * step < frames) out.push_back(a + k * step);
    if (out.size() < count && k * step <= a) out.push_back(a - k * step);
  }
  return out;
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

// The scene of frame `used` (sequence.frames[index]) fused from `count` consecutive frames of the
// sequence about it (as many before as after, the even count's extra one after), each loaded and
// corrected as the dataset's frames are and moved into its camera frame by the sequence's poses.
PointCloud fused_scene(const RgbdSequence& sequence, std::size_t index, const UsedFrame& used,
                       std::size_t count, const std::optional<DepthCalibration>& correction) {
  const std::size_t before = std::min(index, (count - 1) / 2);
  const std::size_t first = index - before;
  const std::size_t last = std::min(sequence.frames.size(), first + count);
  std::vector<PointCloud> clouds;
  clouds.reserve(last - first);  // the frames point into it
  std::vector<DepthFrame> frames{{&used.cloud, Eigen::Isometry3d::Identity()}};
  const Eigen::Isometry3d T_camera_world = used.frame->T_world_camera.inverse();
  for (std::size_t i = first; i < last; ++i) {
    if (i == index) continue;
    PointCloud& cloud = clouds.emplace_back(load_rgbd_frame(sequence.frames[i]));
    if (correction) correction->correction.apply(cloud);
    // The sequence's poses, refined by registering the whole frame onto the scene's: they are
    // tracking's, good to a centimetre, and a fused surface is only as sharp as its frames agree.
    const IcpResult r = register_frames(reduce_for_registration(cloud), used.reduced,
                                        T_camera_world * sequence.frames[i].T_world_camera);
    frames.push_back({&cloud, r.T_target_source});
  }
  return fuse_frames(frames);
}

// A landmark cut in a frame used, and what the scenes need of it.
struct Captured {
  std::size_t frame;
  std::string name;
  Landmark landmark;
  std::vector<std::size_t> box_views;  ///< every view of its box: the scenes keep clear of them
  std::vector<Eigen::Vector3f> seen;   ///< the box's one-view points, for the hidden fraction
};

// Each landmark followed through the scenes after its frame, min_gap to max_gap frames on
// (lmk eval-track): found in the first by a search, then tracked while the camera moves. A frame
// whose pair was left out (its poses disagree) is still tracked through, with no ground truth.
// `scene_of[b]` is frame b's scene in the dataset, if it has one.
std::vector<TrackSequence> sequences_after_capture(
    const Dataset& dataset, const std::vector<std::optional<std::size_t>>& scene_of,
    const std::vector<Captured>& captured, const RgbdDatasetOptions& options) {
  std::vector<TrackSequence> sequences;
  for (const Captured& c : captured) {
    TrackSequence s;
    s.name = c.name;
    s.landmark = c.name;
    for (std::size_t b = c.frame + 1; b < scene_of.size(); ++b) {
      const std::size_t gap = options.frame_stride * (b - c.frame);
      if (gap < options.min_gap || gap > options.max_gap || !scene_of[b]) continue;
      const DatasetScene& scene = dataset.scenes[*scene_of[b]];
      s.frames.push_back(scene.name);
      const DatasetPair pair = dataset.pair(scene, c.name);
      if (!pair.pose_check) continue;
      if (!s.pose_check) s.pose_check = PoseCheck{};
      s.pose_check->translation = std::max(s.pose_check->translation, pair.pose_check->translation);
      s.pose_check->rotation = std::max(s.pose_check->rotation, pair.pose_check->rotation);
    }
    if (s.frames.size() >= 2) sequences.push_back(std::move(s));
  }
  return sequences;
}

// The options a dataset can be built with; lmk::Error naming the first that is not.
void check_options(const RgbdDatasetOptions& options) {
  if (options.frame_stride == 0 || options.min_gap > options.max_gap)
    throw Error("from-rgbd: the frame stride must be positive and min_gap at most max_gap");
  if (options.views < 1 || options.views > 4 || options.view_gap < options.frame_stride ||
      options.view_gap % options.frame_stride != 0) {
    throw Error(
        "from-rgbd: views must be 1 to 4, and the view gap a positive multiple of the frame "
        "stride");
  }
  if (options.fuse < 1 || options.fuse > kMaxFusedFrames) {
    throw Error("from-rgbd: fuse " + std::to_string(options.fuse) + " frames: must be 1 to " +
                std::to_string(kMaxFusedFrames));
  }
  if (options.calibrate_depth && options.depth_correction)
    throw Error("from-rgbd: either fit the depth correction or give one, not both");
}

// The dataset's name: the option's, else the sequence directory's (its parent's for ".").
std::string dataset_name(const std::string& sequence_dir, const RgbdDatasetOptions& options) {
  std::string name = options.name.empty()
                         ? fs::path(sequence_dir).lexically_normal().filename().string()
                         : options.name;
  if (name.empty() || name == ".")
    name = fs::absolute(sequence_dir).lexically_normal().parent_path().filename().string();
  return name;
}

// Every frame_stride-th frame, depth-corrected (`import`'s calibration: fitted on the frames left
// out, or the one given) and reduced for the registration.
std::vector<UsedFrame> used_frames(const RgbdSequence& sequence, const RgbdDatasetOptions& options,
                                   RgbdImport& import) {
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
  for (UsedFrame& f : frames) f.reduced = reduce_for_registration(f.cloud);
  return frames;
}

// The landmarks: the rule's boxes in every frame used, captured and checked as `lmk capture`
// does, in one view and in as many further views as the options ask; with the record of each
// refusal and of each further view's registration.
class LandmarkCutter {
 public:
  LandmarkCutter(const std::vector<UsedFrame>& frames, const RgbdDatasetOptions& options,
                 RgbdImport& import)
      : frames_(frames), options_(options), import_(import) {
    capture_settings_.depth_smoothing = options.depth_smoothing;
    check_settings_.scene.depth_smoothing = options.depth_smoothing;
  }

  // The landmarks of frame `a`'s `boxes`, appended to `captured`.
  void cut_frame(std::size_t a, const std::vector<Box>& boxes, std::vector<Captured>& captured) {
    std::vector<std::size_t> box_views{a};
    for (std::size_t v : further_views(a, frames_.size(), options_.view_gap / options_.frame_stride,
                                       options_.views - 1))
      box_views.push_back(v);
    for (std::size_t k = 0; k < boxes.size(); ++k) {
      ++import_.boxes;
      const std::string name = frames_[a].frame->name + "-" + std::to_string(k);
      std::optional<Landmark> one = keep(name, boxes[k], a, [&] {
        return capture(frames_[a].cloud, boxes[k], name, capture_settings_);
      });
      if (!one) continue;  // a box refused in one view is left out in every number of views
      const std::vector<Eigen::Vector3f> seen = one->points.points;
      captured.push_back({a, name, std::move(*one), box_views, seen});
      for (std::size_t n = 2; n <= box_views.size(); ++n) {
        const std::string name_n = views_landmark_name(name, n);
        std::optional<Landmark> fused = keep(name_n, boxes[k], a, [&] {
          return capture_in_views(a, box_views, n, boxes[k], name_n);
        });
        if (fused) captured.push_back({a, name_n, std::move(*fused), box_views, seen});
      }
    }
  }

  const nlohmann::json& refusals() const { return refusals_; }
  const nlohmann::json& view_records() const { return view_records_; }

 private:
  using Joined = std::variant<ViewRegistration, std::string>;

  // The registration of view `v` onto frame `a` about `box`, from the poses, once per pair of
  // frames: a view it refuses (the reason) leaves the landmarks that need it out.
  const Joined& join(std::size_t a, std::size_t v, const Box& box) {
    auto it = joined_.find({a, v});
    if (it != joined_.end()) return it->second;
    Joined r;
    try {
      r = register_view(
          frames_[a].cloud, frames_[v].cloud,
          frames_[a].frame->T_world_camera.inverse() * frames_[v].frame->T_world_camera, box, 2);
      const ViewRegistration& ok = std::get<ViewRegistration>(r);
      view_records_.push_back({{"frame", frames_[a].frame->name},
                               {"view", frames_[v].frame->name},
                               {"overlap", ok.overlap},
                               {"residual_m", ok.residual},
                               {"moved_m", ok.moved},
                               {"turned_rad", ok.turned}});
    } catch (const Error& e) {
      r = std::string(e.what());
      view_records_.push_back({{"frame", frames_[a].frame->name},
                               {"view", frames_[v].frame->name},
                               {"refused", e.what()}});
    }
    return joined_.emplace(std::make_pair(a, v), r).first->second;
  }

  // The box cut from its first `n` views, the further ones registered onto frame `a`.
  Landmark capture_in_views(std::size_t a, const std::vector<std::size_t>& box_views, std::size_t n,
                            const Box& box, const std::string& name) {
    std::vector<CaptureView> views{{&frames_[a].cloud, Eigen::Isometry3d::Identity()}};
    for (std::size_t i = 1; i < n; ++i) {
      const Joined& r = join(a, box_views[i], box);
      if (const auto* refused = std::get_if<std::string>(&r)) throw Error(*refused);
      views.push_back({&frames_[box_views[i]].cloud, std::get<ViewRegistration>(r).T_first_view});
    }
    return capture_views(views, box, name, capture_settings_);
  }

  // The landmark `cut` makes, with its capture check's findings, when the capture accepts it and
  // it passes the distinctiveness check in its own frame (or keep_warned keeps it anyway);
  // otherwise the reason is tallied.
  std::optional<Landmark> keep(const std::string& name, const Box& box, std::size_t a,
                               const std::function<Landmark()>& cut) {
    std::string why;
    try {
      Landmark landmark = cut();
      landmark.findings = check_capture(landmark, &frames_[a].cloud, check_settings_).findings;
      const CaptureFindings& f = landmark.findings;
      if (!f.found_itself) {
        why = "not found in its own frame";
      } else if (f.look_alikes > 0) {
        why = "matches elsewhere in its own frame";
      }
      if (why.empty() || options_.keep_warned) return landmark;
    } catch (const Error& e) {
      why = refusal_reason(e.what());
    }
    ++import_.refused[why];
    refusals_.push_back(
        {{"landmark", name}, {"reason", why}, {"box", detail::pose_to_json(box.pose)}});
    return std::nullopt;
  }

  const std::vector<UsedFrame>& frames_;
  const RgbdDatasetOptions& options_;
  RgbdImport& import_;
  CaptureSettings capture_settings_;
  FindSettings check_settings_;
  std::map<std::pair<std::size_t, std::size_t>, Joined> joined_;
  nlohmann::json refusals_ = nlohmann::json::array();
  nlohmann::json view_records_ = nlohmann::json::array();
};

// The pair of landmark `c` in frame `b`'s scene, placed by the sequence's poses (T_b_a) and
// checked against the registration of the two whole frames, `reg`; `check` receives the record
// of the check. Left out (nullopt) when the poses and the registration disagree beyond the bound.
std::optional<DatasetPair> checked_pair(const Captured& c, const UsedFrame& b,
                                        const Eigen::Isometry3d& T_b_a, const IcpResult& reg,
                                        const RgbdDatasetOptions& options, nlohmann::json& check) {
  const Eigen::Vector3d centre = c.landmark.box.center();
  DatasetPair pair;
  pair.landmark = c.name;
  pair.in_context = true;
  pair.instances = {T_b_a * c.landmark.box.pose};
  pair.hidden = {hidden_in(c.seen, T_b_a, b)};
  pair.pose_check = PoseCheck{(reg.T_target_source * centre - T_b_a * centre).norm(),
                              rotation_angle_between(reg.T_target_source.linear(), T_b_a.linear())};
  const bool trusted = pair.pose_check->translation <= options.max_pose_disagreement &&
                       pair.pose_check->rotation <= options.max_pose_rotation_disagreement;
  check = {{"landmark", c.name},
           {"disagreement_m", pair.pose_check->translation},
           {"disagreement_rad", pair.pose_check->rotation},
           {"registration_inliers", reg.inliers},
           {"registration_residual_m", reg.final_error},
           {"kept", trusted}};
  if (!trusted) return std::nullopt;
  return pair;
}

// The frames a landmark's views are from `b`, the nearest of them counted (in sequence frames).
std::size_t frames_apart(const Captured& c, std::size_t b, std::size_t stride) {
  std::size_t gap = std::numeric_limits<std::size_t>::max();
  for (std::size_t v : c.box_views) gap = std::min(gap, stride * (b > v ? b - v : v - b));
  return gap;
}

// Frame `b`'s scene: a pair for each landmark cut min_gap to max_gap frames from it whose poses
// the registration confirms, each check appended to `checks`.
DatasetScene scene_of_frame(const std::vector<UsedFrame>& frames, std::size_t b,
                            const std::vector<Captured>& captured, const std::string& setting,
                            const RgbdDatasetOptions& options, RgbdImport& import,
                            nlohmann::json& checks) {
  DatasetScene scene;
  scene.name = frames[b].frame->name;
  scene.file = "scenes/" + scene.name + ".pcd";
  scene.setting = setting;
  std::map<std::size_t, IcpResult> registrations;  // by capture frame
  for (const Captured& c : captured) {
    const std::size_t gap = frames_apart(c, b, options.frame_stride);
    if (gap < options.min_gap || gap > options.max_gap) continue;
    const Eigen::Isometry3d T_b_a =
        frames[b].frame->T_world_camera.inverse() * frames[c.frame].frame->T_world_camera;
    auto it = registrations.find(c.frame);
    if (it == registrations.end())
      it = registrations.emplace(c.frame, register_frames(frames[c.frame], frames[b], T_b_a)).first;
    nlohmann::json check;
    std::optional<DatasetPair> pair = checked_pair(c, frames[b], T_b_a, it->second, options, check);
    check["scene"] = scene.name;
    check["frames_apart"] = gap;
    checks.push_back(check);
    if (!pair) {
      ++import.pairs_left_out;
      continue;
    }
    ++import.pairs;
    scene.pairs.push_back(std::move(*pair));
  }
  return scene;
}

// import.json: how the dataset was made, what was refused and why, and every pose check.
nlohmann::json import_record(const std::string& sequence_dir, const RgbdSequence& sequence,
                             const RgbdDatasetOptions& options, const UserBoxRule& rule,
                             const RgbdImport& import, const LandmarkCutter& cutter,
                             std::size_t landmarks, const nlohmann::json& checks) {
  return {{"format", "lmk-rgbd-import"},
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
          {"views", options.views},
          {"view_gap_frames", options.view_gap},
          {"fused_frames", options.fuse},
          {"view_registrations", cutter.view_records()},
          {"depth_smoothing_px", options.depth_smoothing},
          {"depth_correction", import.depth_calibration
                                   ? detail::depth_calibration_to_json(*import.depth_calibration)
                                   : nlohmann::json(nullptr)},
          {"landmarks", landmarks},
          {"refused", cutter.refusals()},
          {"pose_bound",
           {{"translation_m", options.max_pose_disagreement},
            {"rotation_rad", options.max_pose_rotation_disagreement}}},
          {"pairs", import.pairs},
          {"pairs_left_out", import.pairs_left_out},
          {"pose_checks", checks}};
}

}  // namespace

RgbdImport generate_rgbd_dataset(const std::string& sequence_dir, const std::string& out_dir,
                                 const RgbdDatasetOptions& options) {
  check_options(options);
  const RgbdSequence sequence = read_rgbd_sequence(sequence_dir, options.read);
  RgbdImport import;
  import.layout = sequence.layout;
  Dataset& dataset = import.dataset;
  dataset.name = dataset_name(sequence_dir, options);
  std::error_code ec;
  fs::create_directories(fs::path(out_dir) / "landmarks", ec);
  fs::create_directories(fs::path(out_dir) / "scenes", ec);
  if (ec) throw Error(out_dir + ": cannot create the dataset directory (" + ec.message() + ")");

  const std::vector<UsedFrame> frames = used_frames(sequence, options, import);
  import.box_side = options.box_side.value_or(std::clamp(0.15 * median_depth(frames), 0.08, 0.40));
  UserBoxRule rule;
  rule.box_side = import.box_side;
  rule.max_boxes = options.boxes_per_frame;
  const std::size_t steps = 2 * frames.size();
  std::size_t done = 0;

  LandmarkCutter cutter(frames, options, import);
  std::vector<Captured> captured;
  for (std::size_t a = 0; a < frames.size(); ++a) {
    cutter.cut_frame(a, user_like_boxes(frames[a].cloud, frames[a].frame->intrinsics, rule),
                     captured);
    if (options.progress) options.progress(++done, steps);
  }
  for (const Captured& c : captured) {
    const std::string file = "landmarks/" + c.name + ".lmk";
    save_landmark((fs::path(out_dir) / file).string(), c.landmark);
    dataset.landmarks.push_back({c.name, file, {}});
  }

  // Scenes: every frame used, with each landmark cut min_gap to max_gap frames away from it.
  nlohmann::json checks = nlohmann::json::array();
  std::vector<std::optional<std::size_t>> scene_of(frames.size());  // by frame: its scene
  for (std::size_t b = 0; b < frames.size(); ++b) {
    DatasetScene scene = scene_of_frame(frames, b, captured, dataset.name, options, import, checks);
    if (!scene.pairs.empty()) {
      const std::size_t index = static_cast<std::size_t>(frames[b].frame - sequence.frames.data());
      write_cloud((fs::path(out_dir) / scene.file).string(),
                  options.fuse > 1 ? fused_scene(sequence, index, frames[b], options.fuse,
                                                 import.depth_calibration)
                                   : frames[b].cloud);
      scene_of[b] = dataset.scenes.size();
      dataset.scenes.push_back(std::move(scene));
    }
    if (options.progress) options.progress(++done, steps);
  }
  save_dataset(out_dir, dataset);
  save_track_sequences(out_dir, dataset,
                       sequences_after_capture(dataset, scene_of, captured, options));
  const nlohmann::json record =
      import_record(sequence_dir, sequence, options, rule, import, cutter, captured.size(), checks);
  write_text_atomically(fs::path(out_dir) / "import.json", record.dump(1) + "\n");
  return import;
}

}  // namespace lmk
