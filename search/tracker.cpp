// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/tracker.h"

#include "lmk/geometry/error.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/registration/frame_registration.h"
#include "lmk/search/landmark_index.h"
#include "lmk/search/scene_index.h"

namespace lmk {
namespace {

// The box `box` of the capture frame moved by `T_scene_capture`, grown by `margin` on every side.
Box grown(const Box& box, const Eigen::Isometry3d& T_scene_capture, double margin) {
  return Box(T_scene_capture * box.pose, box.size + Eigen::Vector3d::Constant(2.0 * margin));
}

// Whether a finite point of `frame` lies in `box`: indexing an empty volume is an error, where an
// empty volume around a landmark's prediction is no error but a lost landmark.
bool any_point_in(const PointCloud& frame, const Box& box) {
  for (const Eigen::Vector3f& p : frame.points) {
    if (p.allFinite() && box.contains(p)) return true;
  }
  return false;
}

// The match of `r` nearest to `near` (the pose it was last seen at), or the best one without it.
std::optional<Match> nearest_match(const FindResult& r,
                                   const std::optional<Eigen::Isometry3d>& near) {
  if (r.matches.empty()) return std::nullopt;
  if (!near) return r.matches.front();  // best first
  const Match* best = &r.matches.front();
  for (const Match& m : r.matches) {
    if ((m.T_scene_capture.translation() - near->translation()).norm() <
        (best->T_scene_capture.translation() - near->translation()).norm()) {
      best = &m;
    }
  }
  return *best;
}

}  // namespace

const char* to_string(TrackState state) {
  switch (state) {
    case TrackState::found:
      return "found";
    case TrackState::tracking:
      return "tracking";
    case TrackState::lost:
      return "lost";
    case TrackState::found_again:
      return "found again";
  }
  return "?";
}

const std::vector<std::string>& setting_names(CameraMotion) {
  static const std::vector<std::string> names{"none", "estimated"};
  return names;
}

void validate(const TrackSettings& settings) {
  validate(settings.find);
  validate_settings(settings, "track: ");
}

std::string to_string(const LostCause& cause) {
  switch (cause.reason) {
    case LostReason::none:
      return "";
    case LostReason::nothing_where_predicted:
      return "no point of the frame where it was predicted";
    case LostReason::no_match:
      return "no match";
    case LostReason::turned_down:
      return to_string(cause.rejection);
    case LostReason::not_found:
      return "not found in the frame";
  }
  return "?";
}

// The frame before, reduced for registration, and the camera's last motion: the next one's start.
struct Tracker::CameraMotionEstimate {
  std::optional<PointCloud> before;
  Eigen::Isometry3d last_motion = Eigen::Isometry3d::Identity();
};

struct Tracker::Track {
  std::shared_ptr<const Landmark> landmark;
  std::unique_ptr<LandmarkIndex> index;
  /// T_scene_capture in the last frame it was seen, and in the frame before that when followed:
  /// both in the first frame's coordinates (T_first_frame_), where what stands still stays put.
  std::optional<Eigen::Isometry3d> last;
  std::optional<Eigen::Isometry3d> before;
  bool seen = false;  ///< ever found

  // Constant velocity: the last frame-to-frame motion applied once more.
  Eigen::Isometry3d predicted() const {
    if (!before) return *last;
    return (*last * before->inverse()) * *last;
  }
  void seen_at(const Eigen::Isometry3d& T_first_capture, bool followed) {
    before = followed ? last : std::nullopt;
    last = T_first_capture;
    seen = true;
  }
};

Tracker::Tracker(std::vector<std::shared_ptr<const Landmark>> landmarks, TrackSettings settings)
    : settings_(std::move(settings)) {
  validate(settings_);
  follow_ = settings_.find.resolved();
  *follow_.selection.threshold *= settings_.follow_threshold_factor;
  for (std::shared_ptr<const Landmark>& l : landmarks) {
    Track t;
    t.index = std::make_unique<LandmarkIndex>(l, settings_.find);
    t.landmark = std::move(l);
    tracks_.push_back(std::move(t));
  }
  motion_ = std::make_unique<CameraMotionEstimate>();
}

Tracker::~Tracker() = default;
Tracker::Tracker(Tracker&&) noexcept = default;
Tracker& Tracker::operator=(Tracker&&) noexcept = default;

void Tracker::follow_from(std::size_t landmark, const Eigen::Isometry3d& T_scene_capture) {
  if (landmark >= tracks_.size())
    throw Error("track: no landmark " + std::to_string(landmark) + " (" +
                std::to_string(tracks_.size()) + " followed)");
  Track& t = tracks_[landmark];
  t.last = T_first_frame_ * T_scene_capture;
  t.before.reset();
  t.seen = true;
}

Eigen::Isometry3d Tracker::camera_moved(const PointCloud& frame) {
  if (settings_.camera_motion == CameraMotion::none) return Eigen::Isometry3d::Identity();
  // 4 cm voxels: the frame's large surfaces fix the camera's motion as well as 2 cm ones, in a
  // ninth of the time (18 against 165 ms on a kitchen frame); correspondences and the robust
  // loss scaled with them.
  FrameRegistrationSettings coarse;
  coarse.leaf = 0.04;
  coarse.correspondences = {2.5 * coarse.leaf, {RobustKernel::huber, 0.5 * coarse.leaf}};
  PointCloud reduced = reduce_for_registration(frame, coarse);
  Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
  if (motion_->before && !motion_->before->empty() && !reduced.empty()) {
    // Started from the camera's last motion (it mostly moves smoothly), then from standing still
    // (a shaken camera's next motion is not its last); trusted when it explains half of the frame
    // before, as a frame of the same place a thirtieth of a second later does.
    for (const Eigen::Isometry3d& start : {motion_->last_motion, Eigen::Isometry3d::Identity()}) {
      const IcpResult r = register_frames(*motion_->before, reduced, start, coarse);
      if (2 * r.inliers >= motion_->before->size()) {
        moved = r.T_target_source;
        break;
      }
    }
  }
  motion_->last_motion = moved;
  motion_->before = std::move(reduced);
  return moved;
}

std::unique_ptr<SceneIndex> Tracker::indexed(const PointCloud& frame, const SceneSettings& settings,
                                             FrameWork& work) {
  // The frame's first index builds its image beside its grids, and the frame's other indexes share
  // it. The image is given the camera's intrinsics once an image has fitted them: the frames of a
  // stream come from one camera, and the fit is half of a range image's work
  // (RangeImage::from_cloud checks that they still fit, and fits again where they do not).
  SceneIndexReuse reuse;
  reuse.intrinsics = intrinsics_ ? &*intrinsics_ : nullptr;
  reuse.image = work.image;
  auto index = std::make_unique<SceneIndex>(frame, settings, settings_.find.execution.stop, reuse);
  if (!work.image) work.image = index->shared_range_image();
  if (!intrinsics_ && index->organised() && index->range_image())
    intrinsics_ = index->range_image()->intrinsics();
  return index;
}

std::unique_ptr<SceneIndex> Tracker::index_within(const PointCloud& frame, const Box& volume,
                                                  FrameWork& work) {
  if (!any_point_in(frame, volume)) return nullptr;
  SceneSettings s = settings_.find.scene;
  s.work_volume = volume;
  return indexed(frame, s, work);
}

std::vector<TrackedLandmark> Tracker::update(const PointCloud& frame) {
  // The camera's motion first: T_frame_before, so the first frame's pose in this one follows.
  const Stopwatch registering;
  T_first_frame_ = T_first_frame_ * camera_moved(frame).inverse();
  const Eigen::Isometry3d T_frame_first = T_first_frame_.inverse();
  // Each landmark's time holds its share of the registration, the work of the frame for all.
  const double registration_share =
      tracks_.empty() ? 0.0 : registering.seconds() / static_cast<double>(tracks_.size());
  // The whole frame is indexed at most once, for the landmarks that must be searched in it.
  std::unique_ptr<SceneIndex> whole;
  FrameWork work;  // what this frame's indexes share
  // A search inside `volume` (the whole frame without one); an empty volume finds nothing.
  const auto search = [&](const Track& t, const std::optional<Box>& volume) {
    if (!volume) {
      if (!whole) whole = indexed(frame, settings_.find.scene, work);
      return find_landmark(*whole, *t.index, settings_.find);
    }
    const std::unique_ptr<SceneIndex> near = index_within(frame, *volume, work);
    return near ? find_landmark(*near, *t.index, settings_.find) : FindResult();
  };

  std::vector<TrackedLandmark> out;
  for (Track& t : tracks_) {
    const Stopwatch stopwatch;
    TrackedLandmark now;
    now.name = t.landmark->name;
    if (t.last) {
      // Followed: aligned from the prediction, in the frame around it only.
      const Eigen::Isometry3d predicted = T_frame_first * t.predicted();
      std::optional<FindResult> local;
      if (const std::unique_ptr<SceneIndex> around = index_within(
              frame, grown(t.landmark->box, predicted, settings_.follow_margin), work)) {
        local = find_near_pose(*around, *t.index, follow_, predicted);
      } else {
        now.lost_because.reason = LostReason::nothing_where_predicted;
      }
      if (local && !local->matches.empty()) {
        now.state = TrackState::tracking;
        now.match = local->matches.front();
        t.seen_at(T_first_frame_ * now.match->T_scene_capture, true);
      } else if (local) {
        if (local->rejected.empty()) {
          now.lost_because.reason = LostReason::no_match;
        } else {
          now.lost_because = {LostReason::turned_down, local->rejected.front().reason};
        }
      }
      // Lost here: searched near where it was, then everywhere.
      if (!now.match) {
        const Eigen::Isometry3d was = T_frame_first * *t.last;
        now.match =
            nearest_match(search(t, grown(t.landmark->box, was, settings_.search_margin)), was);
      }
    }
    if (!now.match) {
      now.match = nearest_match(search(t, std::nullopt),
                                t.last ? std::optional(T_frame_first * *t.last) : std::nullopt);
    }
    if (now.match && now.state != TrackState::tracking) {
      now.state = t.seen ? TrackState::found_again : TrackState::found;
      t.seen_at(T_first_frame_ * now.match->T_scene_capture, false);
    } else if (!now.match) {
      now.state = TrackState::lost;
      t.before.reset();  // its motion is unknown now
      if (now.lost_because.reason == LostReason::none)
        now.lost_because.reason = LostReason::not_found;
    }
    if (now.state != TrackState::lost) now.lost_because = {};
    now.seconds = registration_share + stopwatch.seconds();
    out.push_back(std::move(now));
  }
  return out;
}

}  // namespace lmk
