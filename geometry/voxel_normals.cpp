// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/voxel_normals.h"

#include <tbb/parallel_for.h>

#include <string>

#include "lmk/geometry/internal/voxel_table.h"
#include "lmk/geometry/least_axis.h"
#include "lmk/geometry/principal_axes.h"

namespace lmk {
namespace {

// The raw points of one voxel as moments about the voxel's corner: small coordinates keep the
// sums well conditioned in double. Plain arrays: this is accumulated once per raw point.
struct Moments {
  detail::VoxelCoord coord{};
  double count = 0.0;
  double sum[3] = {0.0, 0.0, 0.0};
  double outer[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};  // xx, xy, xz, yy, yz, zz

  void add(double x, double y, double z) {
    count += 1.0;
    sum[0] += x, sum[1] += y, sum[2] += z;
    outer[0] += x * x, outer[1] += x * y, outer[2] += x * z;
    outer[3] += y * y, outer[4] += y * z, outer[5] += z * z;
  }

  // Adds `w`, whose corner lies `d` from this voxel's: for q' = q + d, sum' = sum + n d and
  // outer' = outer + sum d^T + d sum^T + n d d^T.
  void pool(const Moments& w, const double d[3]) {
    static constexpr int kRow[6] = {0, 0, 0, 1, 1, 2}, kCol[6] = {0, 1, 2, 1, 2, 2};
    for (int k = 0; k < 6; ++k) {
      const int a = kRow[k], b = kCol[k];
      outer[k] += w.outer[k] + w.sum[a] * d[b] + d[a] * w.sum[b] + w.count * d[a] * d[b];
    }
    for (int a = 0; a < 3; ++a) sum[a] += w.sum[a] + w.count * d[a];
    count += w.count;
  }

  Eigen::Matrix3d outer_matrix() const {
    Eigen::Matrix3d m;
    m << outer[0], outer[1], outer[2], outer[1], outer[3], outer[4], outer[2], outer[4], outer[5];
    return m;
  }
};

Eigen::Vector3d corner_of(const detail::VoxelCoord& c, double leaf) {
  return Eigen::Vector3d(static_cast<double>(c[0]), static_cast<double>(c[1]),
                         static_cast<double>(c[2])) *
         leaf;
}

Eigen::Vector3d mean_of(const Moments& v) {
  return Eigen::Vector3d(v.sum[0], v.sum[1], v.sum[2]) / v.count;
}

}  // namespace

struct VoxelMoments::Impl {
  Impl(double leaf_size, std::size_t expected_voxels) : leaf(leaf_size), table(expected_voxels) {}
  double leaf;
  detail::VoxelTable table;
  std::vector<Moments> voxels;
};

VoxelMoments::VoxelMoments(const PointCloud& cloud, double leaf_size, const StopCheck& stop) {
  if (!(leaf_size > 0.0) || !std::isfinite(leaf_size)) {
    throw Error("voxel moments: leaf size must be positive and finite, got " +
                std::to_string(leaf_size));
  }
  const double inv_leaf = 1.0 / leaf_size;
  const std::size_t n = cloud.size();
  std::vector<std::uint64_t> keys(n, detail::kNoVoxel);
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
    check_every(stop, i);
    if (is_finite(cloud.points[i])) {
      keys[i] = detail::pack_voxel(detail::voxel_coord(cloud.points[i], inv_leaf));
    }
  });

  // One serial pass: ids in order of first appearance, so the result is deterministic.
  auto impl = std::make_shared<Impl>(leaf_size, n / 8);
  std::vector<Moments>& voxels = impl->voxels;
  voxels.reserve(n / 4 + 16);                 // untouched capacity costs no memory
  std::uint64_t last_key = detail::kNoVoxel;  // neighbouring pixels often share a voxel
  std::uint32_t id = 0;
  for (std::size_t i = 0; i < n; ++i) {
    check_every(stop, i);
    if (keys[i] == detail::kNoVoxel) continue;
    if (keys[i] != last_key) id = impl->table.insert(keys[i]), last_key = keys[i];
    if (id == voxels.size()) {
      voxels.emplace_back();
      voxels.back().coord = detail::voxel_coord(cloud.points[i], inv_leaf);
    }
    Moments& v = voxels[id];
    const Eigen::Vector3d q = cloud.points[i].cast<double>() - corner_of(v.coord, leaf_size);
    v.add(q.x(), q.y(), q.z());
  }
  impl_ = std::move(impl);
}

std::size_t VoxelMoments::size() const { return impl_->voxels.size(); }

std::vector<Eigen::Vector3f> VoxelMoments::centroids() const {
  std::vector<Eigen::Vector3f> out(size());
  tbb::parallel_for(std::size_t{0}, size(), [&](std::size_t id) {
    const Moments& v = impl_->voxels[id];
    out[id] = (corner_of(v.coord, impl_->leaf) + mean_of(v)).cast<float>();
  });
  return out;
}

std::vector<Eigen::Vector3f> VoxelMoments::normals(const Eigen::Vector3d& viewpoint,
                                                   const StopCheck& stop) const {
  const double leaf = impl_->leaf;
  const std::vector<Moments>& voxels = impl_->voxels;
  std::vector<Eigen::Vector3f> out(size(), Eigen::Vector3f::Constant(std::nanf("")));
  tbb::parallel_for(std::size_t{0}, size(), [&](std::size_t id) {
    check_every(stop, id);
    const Moments& v = voxels[id];
    const Eigen::Vector3d local = mean_of(v);  // the centroid, from the corner
    // Pool the block of 2x2x2 voxels whose centre is the voxel corner nearest to the centroid,
    // with moments moved to this voxel's corner.
    std::array<int, 3> step;
    for (int a = 0; a < 3; ++a) step[a] = local[a] < 0.5 * leaf ? -1 : 1;
    Moments block;
    for (int corner_bits = 0; corner_bits < 8; ++corner_bits) {
      detail::VoxelCoord c = v.coord;
      double d[3];
      for (int a = 0; a < 3; ++a) {
        const int offset = ((corner_bits >> a) & 1) ? step[a] : 0;
        c[a] += offset;
        d[a] = offset * leaf;
      }
      const std::uint32_t other = impl_->table.find(detail::pack_voxel(c));
      if (other != detail::VoxelTable::kAbsent) block.pool(voxels[other], d);
    }
    if (block.count < 3.0) return;
    const LeastAxis least = least_axis(covariance_from_moments(
        block.count, Eigen::Vector3d(block.sum[0], block.sum[1], block.sum[2]),
        block.outer_matrix()));
    // Two near-zero spreads mean the points lie on a line; "near zero" allows for the closed-form
    // solver's error.
    if (least.spread[1] <= 1e-6 * least.spread[2]) return;
    Eigen::Vector3d normal = least.axis;
    if (normal.dot(viewpoint - (corner_of(v.coord, leaf) + local)) < 0.0) normal = -normal;
    out[id] = normal.cast<float>();
  });
  return out;
}

PointCloud downsample_with_normals(const PointCloud& cloud, double leaf_size,
                                   const Eigen::Vector3d& viewpoint) {
  const VoxelMoments moments(cloud, leaf_size);
  PointCloud out;
  out.points = moments.centroids();
  out.normals = moments.normals(viewpoint);
  out.set_unorganized();
  out.T_cloud_sensor = cloud.T_cloud_sensor;
  return out;
}

}  // namespace lmk
