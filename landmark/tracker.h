// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Tracker: landmarks followed through a stream of frames (issue #48). A PbD program that locates
// its landmarks once and then moves open-loop drops the object where the bin was when a person
// nudged it; a tracker says where each landmark is now, and when it has lost one.
//
// Per frame and landmark:
// - predict: the last pose moved on by the last frame-to-frame motion (constant velocity);
// - align locally: the frame indexed inside the predicted box and a margin only, and
//   find_near_pose from the prediction (the search's own alignment, metric, selection and
//   confidence), a few milliseconds where a search takes tens;
// - when that match is turned down (error, coverage, empty space, confidence) the landmark is lost
//   in this frame, and searched again: first within `search_margin` of where it was, then in the
//   whole frame; a match found there is "found again".
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/point_cloud.h"
#include "lmk/landmark/find_landmark.h"
#include "lmk/landmark/landmark.h"

namespace lmk {

enum class TrackState {
  found,        ///< found by a search: the first frame, never seen before
  tracking,     ///< followed from the frame before
  lost,         ///< not where it was predicted, nor found by a search
  found_again,  ///< found by a search after it was lost
};
const char* to_string(TrackState state);

struct TrackSettings {
  FindSettings find;  ///< the search's settings, for following and searching alike
  /// m added on every side of the predicted box to index the frame around it: the motion between
  /// two frames a prediction may miss by.
  double follow_margin = 0.10;
  /// m around the box where the landmark was last seen, searched first once it is lost.
  double search_margin = 0.5;
};

/// One landmark in one frame.
struct TrackedLandmark {
  std::string name;
  TrackState state = TrackState::lost;
  std::optional<Match> match;  ///< pose, error, terms, confidence; nothing when lost
  /// Why it was lost: the reason the local match was turned down ("" otherwise).
  std::string lost_because;
  double seconds = 0.0;  ///< this landmark's share of the frame's work
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
  TrackSettings settings_;
  std::vector<Track> tracks_;
};

}  // namespace lmk
