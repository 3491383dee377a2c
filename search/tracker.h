// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Tracker: landmarks followed through a stream of frames (issue #48). A PbD program that locates
// its landmarks once and then moves open-loop drops the object where the bin was when a person
// nudged it; a tracker says where each landmark is now, and when it has lost one.
//
// Per frame, the camera's own motion when asked (CameraMotion::estimated, for frames each in their
// own sensor's frame): the tracks are kept in the first frame's coordinates, where what stands
// still stays put. Then per landmark:
// - predict: the last pose moved on by its last frame-to-frame motion there (constant velocity);
// - align locally: the frame indexed inside the predicted box and a margin only, and
//   find_near_pose from the prediction (the search's own alignment, metric, selection and
//   confidence), a few milliseconds where a search takes tens;
// - a match up to follow_threshold_factor times the threshold is kept (1 by default: the search's
//   own threshold);
// - when that match is turned down (error, coverage, empty space, confidence) the landmark is lost
//   in this frame, and searched again: first within `search_margin` of where it was, then in the
//   whole frame; a match found there is "found again".
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/pinhole_intrinsics.h"
#include "lmk/geometry/point_cloud.h"
#include "lmk/geometry/settings_schema.h"
#include "lmk/landmark/landmark.h"
#include "lmk/search/find_landmark.h"
#include "lmk/search/scene_index.h"

namespace lmk {

enum class TrackState {
  found,        ///< found by a search: the first frame, never seen before
  tracking,     ///< followed from the frame before
  lost,         ///< not where it was predicted, nor found by a search
  found_again,  ///< found by a search after it was lost
};
const char* to_string(TrackState state);

/// How the camera moves between the frames, which a landmark standing still moves by in them.
enum class CameraMotion {
  /// The frames share one fixed frame (a robot's base frame from TF, a bag read into base_link,
  /// `lmk gen` scenes with their sensor pose): what stands still stays put in it.
  none,
  /// The frames are each in their own sensor's frame (a carried camera): each is registered onto
  /// the one before (whole-frame ICP on 4 cm voxels, registration/frame_registration.h, about
  /// 18 ms for a 640 x 480 frame), and a landmark standing still is predicted where the camera's
  /// motion takes it.
  estimated,
};
/// "none", "estimated".
const std::vector<std::string>& setting_names(CameraMotion);

/// The tracker's own settings besides the search's, each described once
/// (geometry/settings_schema.h): the CLI's flags, their limits and the checks of every caller come
/// from describe().
struct TrackSettings {
  FindSettings find;  ///< the search's settings, for following and searching alike
  /// m added on every side of the predicted box to index the frame around it: the motion between
  /// two frames a prediction may miss by.
  double follow_margin = 0.10;
  /// m around the box where the landmark was last seen, searched first once it is lost.
  double search_margin = 0.5;
  /// While following, a match is kept up to this many times the search's error threshold: as the
  /// camera moves, the landmark's other sides turn towards it and the error of the right pose
  /// creeps up. 1 by default: on the real kitchen frames 1.5 kept 900 more landmark-frames
  /// followed and 120 more within 15 mm / 3 degrees, but 300 more over 5 cm off (a drifting
  /// follow held on to), and a wrong pose is worse than a lost one (docs/evaluation.md,
  /// "Tracking").
  double follow_threshold_factor = 1.0;
  CameraMotion camera_motion = CameraMotion::none;

  /// The tracker's fields (not `find`, which describes itself).
  template <class Self, class Visit>
  static void describe(Self& s, Visit&& visit) {
    visit(SettingInfo("follow_margin",
                      "m around the predicted box the frame is searched in while following")
              .within(0.0, 1.0),
          s.follow_margin);
    visit(SettingInfo("search_margin",
                      "m around where a lost landmark was last seen, searched before the whole "
                      "frame")
              .within(0.0, 10.0),
          s.search_margin);
    visit(SettingInfo("follow_threshold_factor",
                      "While following, a match is kept up to this many times the error threshold")
              .within(1.0, 10.0),
          s.follow_threshold_factor);
    visit(SettingInfo("camera_motion",
                      "none (the frames share a fixed frame: a robot's base frame, generated "
                      "scenes) or estimated (frames each in their own camera's frame: each "
                      "registered onto the one before, about 18 ms a frame)")
              .names_of<CameraMotion>(),
          s.camera_motion);
  }
};

/// Throws lmk::Error naming the first field out of its limits ("track: follow_margin
/// (--follow-margin): 5 must be in [0, 1]"), the search's settings included.
void validate(const TrackSettings& settings);

/// Why a landmark was lost in a frame.
enum class LostReason {
  none,                     ///< not lost
  nothing_where_predicted,  ///< no point of the frame lies where it was predicted
  no_match,                 ///< aligned from the prediction, nothing came of it
  turned_down,              ///< the match there was turned down: LostCause::rejection says why
  not_found,  ///< not followed (never seen, or lost before), and the search found none
};

struct LostCause {
  LostReason reason = LostReason::none;
  /// With turned_down: the first test the local match failed (error, coverage, empty space,
  /// confidence).
  RejectionReason rejection = RejectionReason::error_above_threshold;
};

/// "" (none), "no point of the frame where it was predicted", "no match", the rejection's own
/// words ("coverage too low"), "not found in the frame".
std::string to_string(const LostCause& cause);

/// One landmark in one frame.
struct TrackedLandmark {
  std::string name;
  TrackState state = TrackState::lost;
  std::optional<Match> match;  ///< pose, error, terms, confidence; nothing when lost
  LostCause lost_because;      ///< why it was lost (reason none otherwise)
  double seconds = 0.0;        ///< this landmark's share of the frame's work
};

class Tracker {
 public:
  /// Throws lmk::Error for bad settings or a landmark the search cannot use (as find_landmark).
  Tracker(std::vector<std::shared_ptr<const Landmark>> landmarks, TrackSettings settings = {});
  ~Tracker();
  Tracker(Tracker&&) noexcept;
  Tracker& operator=(Tracker&&) noexcept;

  /// The landmarks in the next frame, in the order given. Throws lmk::Error for a frame without a
  /// finite point.
  std::vector<TrackedLandmark> update(const PointCloud& frame);

  /// Landmark `landmark` (its index in the order given) was seen at `T_scene_capture` in the frame
  /// before the next: a search's or a plan's match. The next update follows it from there instead
  /// of searching the whole frame. Throws lmk::Error for an index out of range.
  void follow_from(std::size_t landmark, const Eigen::Isometry3d& T_scene_capture);

  const TrackSettings& settings() const { return settings_; }

 private:
  struct Track;
  struct CameraMotionEstimate;
  /// The camera's motion from the frame before to `frame` (T_frame_before), as the settings say.
  Eigen::Isometry3d camera_moved(const PointCloud& frame);
  /// What the indexes of one frame share: its range image, built by the first of them.
  struct FrameWork {
    std::optional<FrameImage> image;
  };
  /// `frame` indexed with `settings`, sharing `work` with the frame's other indexes.
  std::unique_ptr<SceneIndex> indexed(const PointCloud& frame, const SceneSettings& settings,
                                      FrameWork& work);
  /// `frame` indexed inside `volume` only; null when no point of it lies there.
  std::unique_ptr<SceneIndex> index_within(const PointCloud& frame, const Box& volume,
                                           FrameWork& work);

  TrackSettings settings_;
  FindSettings follow_;  ///< the search's settings while following: the threshold widened
  std::vector<Track> tracks_;
  /// The last frame's pose in the first frame's, through the camera motions: the tracks' poses are
  /// kept in the first frame, where what stands still stays put.
  Eigen::Isometry3d T_first_frame_ = Eigen::Isometry3d::Identity();
  std::unique_ptr<CameraMotionEstimate> motion_;
  /// The camera's intrinsics as the first organised frame's image fitted them: the later
  /// frames' range images reuse them (SceneIndexReuse::intrinsics).
  std::optional<PinholeIntrinsics> intrinsics_;
};

}  // namespace lmk
