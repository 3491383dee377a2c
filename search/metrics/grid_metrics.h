// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The metrics that score with grids instead of k-d trees (registered in error_metrics.cpp).
// Internal.

#include "lmk/landmark/landmark.h"
#include "lmk/search/metrics/error_metrics.h"
#include "lmk/search/scene_index.h"

namespace lmk {

/// The paper's Algorithm 2 with O(1) grid lookups: scene points in the box against the landmark's
/// distance field (its closest-point grid marks the visited landmark points), then the unvisited
/// landmark points against the scene's distance field. Both distances are capped at their bands.
ErrorTerms vdb_metric(const SceneView& scene, const LandmarkView& landmark,
                      const Eigen::Isometry3d& T_scene_capture);

/// Visibility-aware error: each landmark point adds its distance to the scene surface (capped at
/// the scene field's band, which also penalises missing support), and each observed-empty voxel
/// of the landmark that the scene occupies adds its distance to the landmark surface. Scene
/// points in space that was occluded at capture add nothing. The error is the mean of all terms.
ErrorTerms visibility_metric(const SceneView& scene, const LandmarkView& landmark,
                             const Eigen::Isometry3d& T_scene_capture);

/// The visibility metric seen from the scene's sensor ("projective"). A landmark point that the
/// candidate pose places behind a surface the sensor measured nearer, beyond the noise, and
/// outside the candidate's box (hidden_behind()), is hidden: it counts neither in the mean nor in
/// the coverage, where the visibility metric charged it as missing. A partly hidden instance is
/// then judged on what its sensor could see. The occluder must stand kOccluderClearance outside
/// the box: a pose sunk into a surface has its buried part "behind" the very surface it is sunk
/// into, and on the synthetic L-shape scenes such poses matched a plain box at 4.3 mm. An object
/// touching the instance hides nothing for the same reason, and counts as the visibility metric
/// counts it. A pose must still show kMinShownShare of the points: each point short of it costs
/// the band. Scenes without a range image are scored as by the visibility metric.
ErrorTerms projective_metric(const SceneView& scene, const LandmarkView& landmark,
                             const Eigen::Isometry3d& T_scene_capture);

/// The error a true match shows under the visibility metrics at `range` m from the scene's sensor,
/// m: a part from the resolution (the coarse points' leaf) and a part from the depth noise there,
/// in quadrature. Fitted to the true matches of the synthetic `viewpoints` preset, whose simulated
/// Kinect `lmk sensor-check` validated against real frames (median error 2.8 mm at 0.5-1 m, 3.6 mm
/// at 1.5-2 m, 4.3 mm at 2-2.5 m, 5.5 mm at 2.5-3 m: docs/evaluation.md).
double expected_match_error(const SceneSettings& settings, double range);

/// The factor a candidate's visibility error is scaled by at `range` m from the scene's sensor:
/// 1 without settings.threshold_range and up to it; beyond it, expected_match_error() at
/// threshold_range over its value at `range`, so a threshold set where the noise is low holds
/// where it is high.
double match_error_scale(const SceneSettings& settings, double range);

/// How far outside the candidate's box an occluder must stand to hide a point, m. Nearer, it may
/// be the very object the pose was fitted to: on the synthetic L-shape scenes, an L's post fitted
/// to a can at 5.7 mm with its arm "hidden" behind the same can, just outside the box.
inline constexpr double kOccluderClearance = 0.05;

/// The share of a landmark's points a projective pose must show (not hidden). Measured before
/// the occluder clearance: at 0.3, a ball's cap matched on a bowl's curve passed with two thirds
/// of the ball "hidden" inside the bowl (precision 0.891 on the paper preset); at half, none did
/// (1.000), and the occlusion preset's instances 40-60% hidden kept most of their gain (recall
/// 0.548 against 0.571 at 0.3, 0.190 with the visibility metric).
inline constexpr double kMinShownShare = 0.5;

/// How many points a pose showing `shown` of `total` landmark points falls short of
/// kMinShownShare.
std::size_t shown_shortfall(std::size_t shown, std::size_t total);

/// The cosine beyond which a surface turns its face away from a sensor: seen more than 80 degrees
/// from its normal, it returns nothing.
inline constexpr float kTurnedAwayCos = 0.1736f;

/// Whether landmark point j (with its normal), placed by T_scene_capture, turns its face away from
/// a sensor at `sensor` (scene frame). A landmark of several views has points on sides that a
/// sensor in front of it cannot see (capture_views.h); a point without a normal faces every way.
bool turned_away(const Eigen::Vector3f& sensor, const Eigen::Isometry3f& T_scene_capture,
                 const PointCloud& points, std::size_t j);

/// For a landmark of several views placed by T_scene_capture: which of `points` lie behind the
/// landmark's own nearer points seen from `sensor` (scene frame), and so cannot show in a frame
/// taken from there, whatever the scene holds. A z-buffer of the points in a pinhole view along
/// the ray to `centre`, in cells `spacing` wide at the centre's range (a point hides what lies
/// more than `spacing` behind it in its cell and the eight around it, so that the gaps between
/// sampled points do not let a hidden surface through).
std::vector<char> self_hidden(const PointCloud& points, const Eigen::Isometry3f& T_scene_capture,
                              const Eigen::Vector3f& sensor, const Eigen::Vector3f& centre,
                              double spacing);

/// For a landmark of several views placed by T_scene_capture: whether each of `points` shows to a
/// sensor at `sensor`, turned towards it and not self_hidden() behind the landmark's own nearer
/// points (`centre` and `spacing` as there). Where its image ends is the caller's to add.
std::vector<char> facing_sensor(const PointCloud& points, const Eigen::Isometry3f& T_scene_capture,
                                const Eigen::Vector3f& sensor, const Eigen::Vector3f& centre,
                                double spacing);

/// The unseen points a search counts with `landmark`: the scene's setting, except that a landmark
/// of several views never counts its points beyond the scene's image (at least outside-image).
UnseenPoints unseen_points_of(const SceneIndex& scene, const Landmark& landmark);

/// The fast search's coarse score: the mean landmark_point_distance() of `points` placed by
/// T_scene_capture; with `capture_box` (the landmark's box, capture frame), over the points not
/// hidden_behind() an occluder outside the placed box, each point short of kMinShownShare
/// counting the band. With `views` (a landmark of several views), only the points not
/// turned_away() from the scene's sensor, inside its image and not self_hidden() count, and the
/// share is of those.
struct SeveralViews {
  Eigen::Vector3d box_centre;  ///< the landmark box's centre, capture frame
  double spacing = 0.0;        ///< the points' spacing for self_hidden(), m
};
double mean_surface_distance(const SceneIndex& scene, const PointCloud& points,
                             const Eigen::Isometry3f& T_scene_capture,
                             const Box* capture_box = nullptr, const SeveralViews* views = nullptr);

/// Where no occluder may stand for a candidate whose box is `box` (scene frame): the box grown by
/// kOccluderClearance on every side.
Box occluder_free_zone(const Box& box);

/// Whether `q` (scene frame) lies behind a surface the scene's sensor measured nearer than it by
/// more than the noise (three sigma of a measurement at its depth, and at least two paper leaves),
/// with that surface outside `free_zone` (occluder_free_zone() of the candidate's box). False
/// without a range image, outside the view and where nothing was measured.
bool hidden_behind(const SceneIndex& scene, const Eigen::Vector3f& q, const Box& free_zone);

/// Whether the scene's sensor could not have seen `q` (scene frame) at all, as `which` counts it
/// (SceneSettings::unseen_points): outside its image, or on a pixel where it measured nothing.
/// False for `counted`, and for a scene that was no organised frame from its recorded pose: an
/// unorganised cloud's range image is projected through assumed intrinsics.
bool unseen_by_sensor(const SceneIndex& scene, const Eigen::Vector3f& q, UnseenPoints which);

/// Calls visit(e, occupied) for each voxel the scene occupies inside the candidate's box
/// (`occupied`, scene frame) that falls in the landmark's observed-empty space (`e`, capture
/// frame). Both grids share the voxel size, so this finds the same overlap as probing every empty
/// voxel, at a few thousand lookups instead of tens of thousands.
template <class Visit>
void for_each_occupied_empty_voxel(const SceneIndex& scene, const LandmarkView& landmark,
                                   const Eigen::Isometry3d& T_scene_capture, Visit&& visit) {
  const EmptySpaceGrid::Sampler empty(landmark.landmark.empty_space);
  const Eigen::Isometry3f T_capture_scene = T_scene_capture.cast<float>().inverse();
  for (const Eigen::Vector3f& occupied :
       scene.occupancy().occupied_in(landmark.box.transformed(T_scene_capture))) {
    const Eigen::Vector3f e = T_capture_scene * occupied;
    if (empty.is_empty(e)) visit(e, occupied);
  }
}

/// Distance from `q` to the scene surface near the coarse point closest to it: along that point's
/// normal, plus any lateral offset beyond half a coarse voxel diagonal (the coarse points are
/// voxel centroids, so an on-surface query may sit that far beside its nearest one). The band
/// value when no scene point is within the band.
///
/// With `normal` (the query's surface normal, scene frame, facing the sensor that saw it), a query
/// whose normal turns away from the scene surface's by more than 120 degrees is not supported by
/// it: it also gets the band value. Both normals face their sensors, and a sensor sees only the
/// front of a surface, so a landmark face matched back to front (a carton turned half round onto
/// its own two visible faces) is no match; faces meeting at an edge (90 degrees) still are.
float scene_surface_distance(const SceneIndex& scene, const DistanceField::Sampler& field,
                             const Eigen::Vector3f& q, const Eigen::Vector3f* normal = nullptr);

/// scene_surface_distance() of point j of `landmark` (capture frame) moved by T_scene_capture,
/// with its normal when the landmark has normals.
float landmark_point_distance(const SceneIndex& scene, const DistanceField::Sampler& field,
                              const Eigen::Isometry3f& T_scene_capture, const PointCloud& landmark,
                              std::size_t j);

}  // namespace lmk
