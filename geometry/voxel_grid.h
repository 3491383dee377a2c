#pragma once
// Voxel downsampling: one point per occupied voxel, the centroid of the points that fall in it.
// Step 2 of the paper's FindLandmark (leaf 0.005 m).

#include "geometry/point_cloud.h"

namespace lmk {

/// Replaces the finite points of each voxel of side `leaf_size` (metres, grid anchored at the
/// origin) by their centroid. Normals are averaged and renormalised, colours averaged, and a
/// voxel's label is its most frequent label (smallest on ties). The output is unorganised and
/// ordered by voxel coordinates (x slowest, z fastest), so it is deterministic whatever the thread
/// count. Throws lmk::Error for a non-positive leaf or a cloud too large for the leaf.
PointCloud voxel_downsample(const PointCloud& cloud, double leaf_size);

}  // namespace lmk
