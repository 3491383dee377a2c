// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The sensor-aware error metric (issue #16, part 3), registered as "sensor". Internal.

#include "lmk/search/metrics/error_metrics.h"
#include "lmk/search/scene_index.h"

namespace lmk {

/// Sensor-aware error, in units of the expected depth noise (geometry/depth_noise.h):
///
/// - Each landmark point, placed by the candidate pose, is looked up in the scene's range image.
///   Behind a nearer scene surface, turned away from the scene's sensor, outside its view or where
///   it measured nothing, the point is unknown: it counts neither way. Where the sensor saw
///   clearly past it, to a surface more than kOccluding sigma behind, the point is seen through:
///   the strongest evidence against the match, it costs the cap. Otherwise its residual (its
///   distance to the scene surface, at most its depth gap) is divided by sigma, the noise expected
///   of a point captured at its capture depth and measured again at its scene depth, and capped.
/// - Coverage is the share of the points that should be visible with a residual below the
///   support level, over at least a fifth of all points (so that a pose seen nowhere is no match).
/// - Empty space is seen the same way: each observed-empty voxel of the landmark more than
///   kOccluding sigma from its surface is violated when the image holds a surface within a sigma of
///   its depth, confirmed empty when the surface lies more than kOccluding sigma behind, unknown
///   otherwise; probes are the voxels observed either way. When less than kMinEmptyObserved of
///   the landmark's free space is observed, the pose has no evidence and the error is the cap.
/// - The error is the mean of the points' terms. Without a range image (an unorganised cloud whose
///   sensor pose does not explain it), every point counts as visible, and empty space is tested as
///   the visibility metric tests it, beyond two sigma of the landmark's surface.
ErrorTerms sensor_metric(const SceneView& scene, const LandmarkView& landmark,
                         const Eigen::Isometry3d& T_scene_capture);

/// The sensor metric's fit of `points` (capture frame, with their normals if any, captured from
/// `capture_sensor`) placed by T_scene_capture: the capped sigma residuals of the points that
/// should be visible, and how the others were classified.
struct SensorFit {
  double cost_sum = 0.0;  ///< sigma, over the visible points
  std::size_t visible = 0, supported = 0, unseen = 0, seen_through = 0;
  /// cost_sum over the visible points, but over at least a fifth of all points, each point short
  /// of that costing the cap: a pose seen nowhere fits nothing.
  double mean_cost() const;
  /// Supported over visible points, over at least a fifth of all points.
  double coverage() const;
};
/// The empty space's part of the fast search's coarse score for the sensor metric, in sigma: the
/// cap times the share of the observed ones among `centres` (observed-empty voxel centres of
/// `landmark`, capture frame, `distances` from its surface) that the scene's sensor measured a
/// surface at; the cap when too few are observed; 0 without a range image.
double empty_space_penalty(const SceneIndex& index, const Landmark& landmark,
                           const std::vector<Eigen::Vector3f>& centres,
                           const std::vector<float>& distances,
                           const Eigen::Isometry3f& T_scene_capture);

/// The share of the observed-empty voxels of `landmark` (`distances` from its surface, as
/// LandmarkIndex::empty_distances()) placed by T_scene_capture that the scene's sensor sees empty:
/// a surface measured clearly behind them. Voxels it sees occupied, hidden behind a nearer surface,
/// without a return or outside its view count against it; those within the noise of the landmark's
/// surface are not counted. NaN without a range image or a tested voxel.
double empty_space_seen_empty(const SceneIndex& index, const Landmark& landmark,
                              const std::vector<float>& distances,
                              const Eigen::Isometry3d& T_scene_capture);

SensorFit sensor_fit(const SceneIndex& index, const PointCloud& points,
                     const Eigen::Vector3f& capture_sensor,
                     const Eigen::Isometry3f& T_scene_capture);

}  // namespace lmk
