#pragma once
// The metrics that score with grids instead of k-d trees (registered in error_metrics.cpp).
// Internal.

#include "landmark/error_metrics.h"
#include "landmark/landmark.h"
#include "landmark/scene_index.h"

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
