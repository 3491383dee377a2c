#pragma once
// Voxel downsampling that also gives each centroid a surface normal, in one pass over the raw
// points. The scene index needs both for every frame; a k-nearest-neighbour normal search over the
// downsampled cloud cost more than everything else in building it.

#include "geometry/point_cloud.h"

namespace lmk {

/// One point per occupied voxel of side `leaf_size` (the centroid, as voxel_downsample), with a
/// normal from the principal axes of the raw points in the 2x2x2 block of voxels nearest to the
/// centroid: a neighbourhood about two leaves across, pooled from per-voxel moments. The normal
/// faces cloud.sensor_origin(); it is NaN where the block's points lie on a line or number fewer
/// than three. Colours and labels are dropped. The output is unorganised, in order of each voxel's
/// first point in the input, so it does not depend on the thread count. Throws lmk::Error for a
/// non-positive leaf or a cloud too large for the leaf.
PointCloud voxel_downsample_with_normals(const PointCloud& cloud, double leaf_size);

}  // namespace lmk
