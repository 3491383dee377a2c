// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Voxel downsampling: one point per occupied voxel, the centroid of the points that fall in it.
// Step 2 of the paper's FindLandmark (leaf 0.005 m).

#include "lmk/geometry/point_cloud.h"
#include "lmk/geometry/stop_check.h"

namespace lmk {

/// The finest voxel leaf lmk accepts anywhere (scene leaves, capture leaves, grid bands), m. A
/// Kinect's pixels lie about 1 mm apart at 0.6 m, so a finer leaf resolves nothing more, while the
/// grids grow with the cube of its inverse: 10 um made OpenVDB fail and a capture at 0.5 mm took
/// 70 s.
inline constexpr double kMinLeafSize = 0.001;

/// Replaces the finite points of each voxel of side `leaf_size` (metres, grid anchored at the
/// origin) by their centroid. Normals are averaged and renormalised, colours averaged, and a
/// voxel's label is its most frequent label (smallest on ties). The output is unorganised and
/// ordered by voxel coordinates (x slowest, z fastest), so it is deterministic whatever the thread
/// count. Throws lmk::Error for a non-positive leaf or a cloud too large for the leaf. `stop` is
/// called between pieces of the work (geometry/stop_check.h).
PointCloud voxel_downsample(const PointCloud& cloud, double leaf_size, const StopCheck& stop = {});

}  // namespace lmk
