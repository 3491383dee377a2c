// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/voxel_grid.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <cmath>
#include <string>
#include <unordered_map>

#include "lmk/geometry/detail/voxel_key.h"
#include "lmk/geometry/error.h"

namespace lmk {
namespace {

struct KeyedIndex {
  std::uint64_t key;
  Index index;
  bool operator<(const KeyedIndex& o) const { return key != o.key ? key < o.key : index < o.index; }
};

std::int32_t most_frequent_label(const PointCloud& cloud, const KeyedIndex* begin,
                                 const KeyedIndex* end) {
  std::unordered_map<std::int32_t, int> counts;
  for (const KeyedIndex* it = begin; it != end; ++it) ++counts[cloud.labels[it->index]];
  std::int32_t best = 0;
  int best_count = 0;
  for (const auto& [label, n] : counts) {
    if (n > best_count || (n == best_count && label < best)) best = label, best_count = n;
  }
  return best;
}

}  // namespace

PointCloud voxel_downsample(const PointCloud& cloud, double leaf_size) {
  if (!(leaf_size > 0.0) || !std::isfinite(leaf_size)) {
    throw Error("voxel_downsample: leaf size must be positive and finite, got " +
                std::to_string(leaf_size));
  }
  const double inv_leaf = 1.0 / leaf_size;

  std::vector<KeyedIndex> keyed;
  keyed.reserve(cloud.size());
  for (Index i = 0; i < cloud.size(); ++i) {
    if (is_finite(cloud.points[i]))
      keyed.push_back({detail::pack_voxel(detail::voxel_coord(cloud.points[i], inv_leaf)), i});
  }
  // Sorting by (key, index) is a total order, so the parallel sort is deterministic.
  tbb::parallel_sort(keyed.begin(), keyed.end());

  std::vector<std::size_t> starts;  // first entry of each voxel run, plus the end
  for (std::size_t k = 0; k < keyed.size(); ++k) {
    if (k == 0 || keyed[k].key != keyed[k - 1].key) starts.push_back(k);
  }
  const std::size_t voxels = starts.size();
  starts.push_back(keyed.size());

  PointCloud out;
  out.T_cloud_sensor = cloud.T_cloud_sensor;
  out.points.resize(voxels);
  if (cloud.has_normals()) out.normals.resize(voxels);
  if (cloud.has_colors()) out.colors.resize(voxels);
  if (cloud.has_labels()) out.labels.resize(voxels);

  tbb::parallel_for(std::size_t{0}, voxels, [&](std::size_t v) {
    const KeyedIndex* begin = keyed.data() + starts[v];
    const KeyedIndex* end = keyed.data() + starts[v + 1];
    const double n = static_cast<double>(end - begin);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();
    Eigen::Vector4d color_sum = Eigen::Vector4d::Zero();
    for (const KeyedIndex* it = begin; it != end; ++it) {
      sum += cloud.points[it->index].cast<double>();
      if (cloud.has_normals() && is_finite(cloud.normals[it->index])) {
        normal_sum += cloud.normals[it->index].cast<double>();
      }
      if (cloud.has_colors()) {
        const Color& c = cloud.colors[it->index];
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
