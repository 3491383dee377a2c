// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The finite points of a cloud grouped by voxel, for the filters and grids that visit a voxel's
// points together. Internal.
//
// Voxels are numbered in order of first appearance (one VoxelTable probe per point) and each
// voxel's points kept in index order (a counting sort): no sort of the points, and the result does
// not depend on anything but the cloud's order.

#include <cstdint>
#include <vector>

#include "lmk/geometry/internal/voxel_table.h"
#include "lmk/geometry/point_cloud.h"
#include "lmk/geometry/stop_check.h"

namespace lmk::detail {

struct VoxelBuckets {
  VoxelTable table;                 ///< packed voxel key -> voxel id
  std::vector<std::uint64_t> keys;  ///< packed key of each voxel id
  std::vector<std::size_t> starts;  ///< points of voxel id: members[starts[id], starts[id + 1])
  std::vector<Index> members;       ///< point indices, voxel by voxel, ascending within a voxel
};

/// Voxels of side 1 / inv_leaf anchored at the origin. Throws lmk::Error when the cloud spans too
/// many voxels for a key (voxel_coord). `stop` is called between pieces of the work.
VoxelBuckets bucket_by_voxel(const PointCloud& cloud, double inv_leaf, const StopCheck& stop = {});

}  // namespace lmk::detail
