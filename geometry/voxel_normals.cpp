// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/voxel_normals.h"

#include <tbb/parallel_for.h>

#include <string>
#include <type_traits>

#include "lmk/geometry/internal/voxel_table.h"
#include "lmk/geometry/internal/voxel_tiles.h"
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
  // outer' = outer + sum d^T + d sum^T + n d d^T. Bit a of kMoved says whether d[a] is not zero:
  // the terms of a zero d[a] are exact zeros and left out, the rest summed in the same order (the
  // same sums: a block starts at +0, which a signed zero cannot change).
  template <int kMoved>
  void pool(const Moments& w, const double d[3]) {
    static constexpr int kRow[6] = {0, 0, 0, 1, 1, 2}, kCol[6] = {0, 1, 2, 1, 2, 2};
    const auto moved = [](int a) { return ((kMoved >> a) & 1) != 0; };
    for (int k = 0; k < 6; ++k) {
      const int a = kRow[k], b = kCol[k];
      double term = w.outer[k];
      if (moved(b)) term += w.sum[a] * d[b];
      if (moved(a)) term += d[a] * w.sum[b];
      if (moved(a) && moved(b)) term += w.count * d[a] * d[b];
      outer[k] += term;
    }
    for (int a = 0; a < 3; ++a) sum[a] += moved(a) ? w.sum[a] + w.count * d[a] : w.sum[a];
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
  explicit Impl(double leaf_size) : leaf(leaf_size) {}
  double leaf;
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
  auto impl = std::make_shared<Impl>(leaf_size);
  detail::VoxelTable table(n / 8);
  std::vector<Moments>& voxels = impl->voxels;
  voxels.reserve(n / 4 + 16);  // untouched capacity costs no memory
  // Neighbouring pixels often share a voxel: a run of them adds to a copy of its voxel held in
  // registers, stored back when the run ends, rather than to the voxel's record in memory one point
  // at a time. The same additions in the same order: the same sums.
  std::uint64_t run_key = detail::kNoVoxel;
  std::uint32_t run_id = 0;
  Moments run;
  Eigen::Vector3d corner = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    check_every(stop, i);
    if (keys[i] == detail::kNoVoxel) continue;
    if (keys[i] != run_key) {
      if (run_key != detail::kNoVoxel) voxels[run_id] = run;
      run_key = keys[i];
      run_id = table.insert(run_key);
      if (run_id == voxels.size()) {
        voxels.emplace_back();
        voxels.back().coord = detail::voxel_coord(cloud.points[i], inv_leaf);
      }
      run = voxels[run_id];
      corner = corner_of(run.coord, leaf_size);
    }
    const Eigen::Vector3d q = cloud.points[i].cast<double>() - corner;
    run.add(q.x(), q.y(), q.z());
  }
  if (run_key != detail::kNoVoxel) voxels[run_id] = run;
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
  // The blocks are pooled from a copy of the voxels in tile order, where neighbours sit together.
  const detail::VoxelTiles tiles(voxels.size(), [&](std::size_t id) { return voxels[id].coord; });
  std::vector<Moments> by_tile(voxels.size());
  for (std::size_t k = 0; k < by_tile.size(); ++k) by_tile[k] = voxels[tiles.order()[k]];
  std::vector<Eigen::Vector3f> out(size(), Eigen::Vector3f::Constant(std::nanf("")));
  tbb::parallel_for(std::size_t{0}, size(), [&](std::size_t id) {
    check_every(stop, id);
    const Moments& v = voxels[id];
    const Eigen::Vector3d local = mean_of(v);  // the centroid, from the corner
    // Pool the block of 2x2x2 voxels whose centre is the voxel corner nearest to the centroid,
    // with moments moved to this voxel's corner.
    std::array<int, 3> step;
    for (int a = 0; a < 3; ++a) step[a] = local[a] < 0.5 * leaf ? -1 : 1;
    // The voxel itself first, then its neighbours in the order of the bits of their offsets. One
    // hint serves the block's lookups: its voxels mostly share a tile.
    Moments block;
    block.pool<0>(v, nullptr);
    detail::VoxelTiles::Hint hint;
    const auto add_neighbour = [&](auto moved) {
      constexpr int kMoved = decltype(moved)::value;
      detail::VoxelCoord c = v.coord;
      double d[3] = {0.0, 0.0, 0.0};
      for (int a = 0; a < 3; ++a) {
        if (((kMoved >> a) & 1) == 0) continue;
        c[a] += step[a];
        d[a] = step[a] * leaf;
      }
      const std::uint32_t other = tiles.find(c, hint);
      if (other != detail::VoxelTiles::kAbsent) block.pool<kMoved>(by_tile[other], d);
    };
    add_neighbour(std::integral_constant<int, 1>{});
    add_neighbour(std::integral_constant<int, 2>{});
    add_neighbour(std::integral_constant<int, 3>{});
    add_neighbour(std::integral_constant<int, 4>{});
    add_neighbour(std::integral_constant<int, 5>{});
    add_neighbour(std::integral_constant<int, 6>{});
    add_neighbour(std::integral_constant<int, 7>{});
    if (block.count < 3.0) return;
    const PrincipalAxes pca = principal_axes_from_moments(
        block.count, Eigen::Vector3d(block.sum[0], block.sum[1], block.sum[2]),
        block.outer_matrix());
    // Two near-zero spreads mean the points lie on a line; "near zero" allows for the closed-form
    // solver's error.
    if (pca.spread[1] <= 1e-6 * pca.spread[2]) return;
    Eigen::Vector3d normal = pca.axes.col(0);
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
