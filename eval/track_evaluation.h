// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Tracking evaluated against a dataset's sequences (issue #48; lmk eval-track, docs/evaluation.md
// "Tracking"): each sequence's landmark followed through its frames by the Tracker
// (search/tracker.h) and every frame's state and pose compared with the ground truth.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lmk/datasets/track_sequences.h"
#include "lmk/search/tracker.h"

namespace lmk {

/// When a tracked pose counts as right: the 10 mm and 5 degrees by default, tighter than
/// the search's protocol (25.4 mm, 15 degrees) because a tracked pose is acted on at once.
struct TrackTolerance {
  double translation = 0.010;          ///< m, between box centres
  double rotation = 5.0 * M_PI / 180;  ///< rad, modulo the landmark's symmetry
};

/// What the ground truth says of one frame.
enum class FrameTruth {
  in_view,  ///< the landmark is there, and seen (less than kIgnoredHiddenFraction hidden)
  away,     ///< it is not in the frame (carried away, or out of view)
  unknown,  ///< the dataset does not say (a real frame whose poses could not be checked)
};

struct TrackedFrame {
  TrackState state = TrackState::lost;
  FrameTruth truth = FrameTruth::unknown;
  bool has_pose = false;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< the tracked box, when has_pose
  double translation_error = 0.0;  ///< m, when both a pose and an in-view truth exist
  double rotation_error = 0.0;     ///< rad
  double error = 0.0;              ///< the match's, in the metric's unit, when has_pose
  /// The match's calibrated confidence (NaN without a calibration) and how far its freest motion
  /// moves it within the noise (MatchConfidence::freedom), when has_pose.
  double confidence = 0.0, freedom = 0.0;
  double seconds = 0.0;
};

struct SequenceResult {
  std::string name, landmark;
  std::vector<TrackedFrame> frames;
  std::optional<Carry> carry;
  std::optional<PoseCheck> pose_check;  ///< the ground truth's own uncertainty (real sequences)

  std::size_t in_view = 0;          ///< frames where the landmark is in view
  std::size_t within = 0;           ///< of those, tracked within the tolerance
  std::size_t lost_in_view = 0;     ///< in view, and said lost
  std::size_t wrong_in_view = 0;    ///< in view, and a pose outside the tolerance
  std::size_t pose_while_away = 0;  ///< not in the frame, and a pose said anyway
  /// Frames from the carry until the tracker no longer claims its old place (lost or found
  /// elsewhere): 0 when it noticed in the first frame; nothing when it never did.
  std::optional<std::size_t> carry_noticed_after;
  /// Frames from the landmark's return until a pose within the tolerance: 0 in the frame itself.
  std::optional<std::size_t> refound_after;
};

struct TrackEvaluation {
  std::string dataset;
  TrackTolerance tolerance;
  std::vector<SequenceResult> sequences;
  double seconds = 0.0;  ///< wall time

  std::size_t in_view() const;
  std::size_t within() const;
  /// Per landmark-frame, s.
  double median_seconds() const;
  double percentile_seconds(double q) const;
};

struct TrackEvaluationOptions {
  TrackSettings track;  ///< the scene's up axis is taken from each sequence's first frame
  TrackTolerance tolerance;
  /// Only the sequences whose names contain this; empty: all.
  std::string only;
  DatasetFiles files = DatasetFiles::inside;
  /// Called after each frame, with (frames done, frames in all).
  std::function<void(std::size_t, std::size_t)> progress;
};

/// Follows every sequence of the dataset in `dir` and scores it. Throws lmk::Error for a dataset
/// without sequences.json, or one that names what it does not hold.
TrackEvaluation evaluate_tracking(const std::string& dir, const TrackEvaluationOptions& options);

/// The evaluation as a table, a line per sequence and the totals (what lmk eval-track prints).
std::string tracking_report(const TrackEvaluation& evaluation);
/// The evaluation as JSON text: the totals, and per sequence its figures and every frame.
std::string tracking_json(const TrackEvaluation& evaluation);

}  // namespace lmk
