// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/voxel_grid.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <cmath>
#include <numeric>
#include <string>
#include <unordered_map>

#include "lmk/geometry/detail/voxel_buckets.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/internal/voxel_key.h"

namespace lmk {
namespace {

std::int32_t most_frequent_label(const PointCloud& cloud, const Index* begin, const Index* end) {
  std::unordered_map<std::int32_t, int> counts;
  for (const Index* it = begin; it != end; ++it) ++counts[cloud.labels[*it]];
  std::int32_t best = 0;
  int best_count = 0;
  for (const auto& [label, n] : counts) {
    if (n > best_count || (n == best_count && label < best)) best = label, best_count = n;
  }
  return best;
}

}  // namespace

PointCloud voxel_downsample(const PointCloud& cloud, double leaf_size, const StopCheck& stop) {
  if (!(leaf_size > 0.0) || !std::isfinite(leaf_size)) {
    throw Error("voxel_downsample: leaf size must be positive and finite, got " +
                std::to_string(leaf_size));
  }
  const double inv_leaf = 1.0 / leaf_size;

  // The points of each voxel in index order, with no sort of the points; only the voxels, far
  // fewer, are sorted by key for the output order.
  if (stop) stop();
  const detail::VoxelBuckets buckets = detail::bucket_by_voxel(cloud, inv_leaf, stop);
  if (stop) stop();
  const std::vector<std::uint64_t>& keys = buckets.keys;
  const std::vector<std::size_t>& starts = buckets.starts;
  const std::vector<Index>& members = buckets.members;
  const std::size_t voxels = keys.size();
  std::vector<std::uint32_t> order(voxels);  // voxel ids by key: x slowest, z fastest
  std::iota(order.begin(), order.end(), 0u);
  tbb::parallel_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });

  if (stop) stop();
  PointCloud out;
  out.T_cloud_sensor = cloud.T_cloud_sensor;
  out.points.resize(voxels);
  if (cloud.has_normals()) out.normals.resize(voxels);
  if (cloud.has_colors()) out.colors.resize(voxels);
  if (cloud.has_labels()) out.labels.resize(voxels);

  tbb::parallel_for(std::size_t{0}, voxels, [&](std::size_t v) {
    check_every(stop, v);
    const Index* begin = members.data() + starts[order[v]];
    const Index* end = members.data() + starts[order[v] + 1];
    const double n = static_cast<double>(end - begin);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();
    Eigen::Vector4d color_sum = Eigen::Vector4d::Zero();
    for (const Index* it = begin; it != end; ++it) {
      sum += cloud.points[*it].cast<double>();
      if (cloud.has_normals() && is_finite(cloud.normals[*it])) {
        normal_sum += cloud.normals[*it].cast<double>();
      }
      if (cloud.has_colors()) {
        const Color& c = cloud.colors[*it];
        color_sum += Eigen::Vector4d(c.r, c.g, c.b, c.a);
      }
    }
    out.points[v] = (sum / n).cast<float>();
    if (cloud.has_normals()) {
      const double len = normal_sum.norm();
      out.normals[v] = len > 0.0 ? (normal_sum / len).cast<float>().eval()
                                 : Eigen::Vector3f::Constant(std::nanf(""));
    }
    if (cloud.has_colors()) {
      const Eigen::Vector4d c = (color_sum / n).array().round();
      out.colors[v] = {static_cast<std::uint8_t>(c[0]), static_cast<std::uint8_t>(c[1]),
                       static_cast<std::uint8_t>(c[2]), static_cast<std::uint8_t>(c[3])};
    }
    if (cloud.has_labels()) out.labels[v] = most_frequent_label(cloud, begin, end);
  });
  out.set_unorganized();
  return out;
}

}  // namespace lmk
