// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A match's evidence (match_confidence.h), computed from what the search has already met: every
// candidate it aligned and scored (the competitors), the scene's distance field and normals (the
// support and freedom), and the depth noise at the match's range (the error's uncertainty).
// Nothing here changes a match or its order. Internal.

#include <optional>
#include <vector>

#include "lmk/search/confidence/confidence_calibration.h"
#include "lmk/search/find_result.h"
#include "lmk/search/find_settings.h"
#include "lmk/search/metrics/error_metrics.h"
#include "lmk/search/scene_index.h"

namespace lmk::detail {

struct ConfidenceInput {
  const SceneIndex& index;
  const Landmark& landmark;
  /// The landmark's points at the scene's coarse leaf, capture frame: the support is counted on
  /// them, about one per independent patch of noise.
  const PointCloud& coarse_landmark;
  const KdTree& landmark_tree;  ///< the landmark's points, capture frame
  /// The search's metric and its view of the landmark: the poses along a match's freest motion
  /// that no candidate stood at are scored with them (probe_freest_motion()).
  const ErrorMetric& metric;
  const LandmarkView& view;
  const SelectionSettings& selection;
  /// The calibration to apply; null when none was fitted for the metric (calibration_for()).
  const ConfidenceCalibration* calibration;
  /// A flat landmark's plane normal, capture frame (flat_normal()): such a landmark is the same
  /// wherever it lies on its plane, so poses on the match's plane are no rivals and its freedom
  /// within the plane is not probed.
  std::optional<Eigen::Vector3d> flat_normal = std::nullopt;
  /// A flat landmark's empty voxels' distances from its surface (LandmarkIndex::empty_distances()):
  /// how much of its free space the scene sees empty is measured with them
  /// (MatchConfidence::free_space_seen). Null for other landmarks.
  const std::vector<float>* empty_distances = nullptr;
};

/// The share of the empty-space allowance of `selection` that terms `t` use
/// (MatchConfidence::intrusion).
double empty_space_intrusion(const ErrorTerms& t, const SelectionSettings& selection);

/// Whether `candidate` could have been a match but for its error: it passes the coverage and the
/// empty-space tests of `selection` (a pose that fails them is no alternative a robot could take).
bool plausible_alternative(const Match& candidate, const SelectionSettings& selection);

/// The match moved along its freest motion (`confidence.freest`, measured first): slid, or turned
/// about its axis, by whole same-pose steps (kSamePoseDistance, kSamePoseAngle) out to the
/// landmark box's extent, each pose scored with the search's metric. A search whose candidates
/// all converged near a wrong spot on a long edge met no rival there; the truth is one of these.
/// Empty when the match's freedom is under half a same-pose step: a pose the scene pins.
std::vector<Match> probe_freest_motion(const ConfidenceInput& input, const Match& match,
                                       const MatchConfidence& confidence);

/// The evidence of `match` against `pool`, every candidate the search scored (the match itself may
/// be among them: as the same pose, it is no rival), and its calibrated probability and doubt
/// line.
MatchConfidence assess_match(const ConfidenceInput& input, const Match& match,
                             const std::vector<const Match*>& pool);

}  // namespace lmk::detail
