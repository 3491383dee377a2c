// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/detail/voxel_buckets.h"

namespace lmk::detail {

VoxelBuckets bucket_by_voxel(const PointCloud& cloud, double inv_leaf, const StopCheck& stop) {
  VoxelBuckets b{VoxelTable(cloud.size() / 8), {}, {}, {}};
  std::vector<std::uint32_t> voxel_of(cloud.size(), VoxelTable::kAbsent);
  for (Index i = 0; i < cloud.size(); ++i) {
    check_every(stop, i);
    if (!is_finite(cloud.points[i])) continue;
    const std::uint64_t key = pack_voxel(voxel_coord(cloud.points[i], inv_leaf));
    voxel_of[i] = b.table.insert(key);
    if (voxel_of[i] == b.keys.size()) b.keys.push_back(key);
  }
  b.starts.assign(b.keys.size() + 1, 0);
  for (const std::uint32_t id : voxel_of) {
    if (id != VoxelTable::kAbsent) ++b.starts[id + 1];
  }
  for (std::size_t v = 0; v + 1 < b.starts.size(); ++v) b.starts[v + 1] += b.starts[v];
  b.members.resize(b.starts.back());
  std::vector<std::size_t> fill(b.starts.begin(), b.starts.end() - 1);
  for (Index i = 0; i < cloud.size(); ++i) {
    check_every(stop, i);
    if (voxel_of[i] != VoxelTable::kAbsent) b.members[fill[voxel_of[i]]++] = i;
  }
  return b;
}

}  // namespace lmk::detail
