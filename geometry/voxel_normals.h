// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Voxel downsampling that also gives each centroid a surface normal, from one pass over the raw
// points. The scene index needs both for every frame; a k-nearest-neighbour normal search over the
// downsampled cloud cost more than everything else in building it.

#include <memory>

#include "lmk/geometry/point_cloud.h"
#include "lmk/geometry/stop_check.h"

namespace lmk {

/// The raw points of each occupied voxel (side `leaf_size`, grid anchored at the origin) as
/// moments: count, sum and sum of outer products, gathered in one pass over the cloud. Centroids
/// and normals both come from them, so a caller can use the centroids while the normals are being
/// pooled. Voxels are in order of their first point in the input. Immutable once built; copies
/// share the moments.
class VoxelMoments {
 public:
  /// Throws lmk::Error for a non-positive leaf or a cloud too large for the leaf.
  /// `stop` is called between pieces of the work (geometry/stop_check.h).
  VoxelMoments(const PointCloud& cloud, double leaf_size, const StopCheck& stop = {});

  std::size_t size() const;  ///< occupied voxels
  /// The centroid of each voxel's points.
  std::vector<Eigen::Vector3f> centroids() const;
  /// Each voxel's normal: the principal axes of the raw points in the 2x2x2 block of voxels
  /// nearest to its centroid, a neighbourhood about two leaves across, facing `viewpoint`. NaN
  /// where the block's points lie on a line or number fewer than three.
  std::vector<Eigen::Vector3f> normals(const Eigen::Vector3d& viewpoint,
                                       const StopCheck& stop = {}) const;

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;
};

/// The cloud downsampled to its voxel centroids, each with the normal VoxelMoments::normals gives
/// it, facing `viewpoint`. Two clouds reduced this way have comparable normals whatever
/// their own normals were: the fast search builds its landmark model like the scene's coarse cloud,
/// so that point pair features of the two agree.
PointCloud downsample_with_normals(const PointCloud& cloud, double leaf_size,
                                   const Eigen::Vector3d& viewpoint);

}  // namespace lmk
