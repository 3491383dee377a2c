// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/normals.h"

#include <tbb/parallel_for.h>

#include "lmk/geometry/error.h"
#include "lmk/geometry/principal_axes.h"

namespace lmk {

std::vector<Eigen::Vector3f> estimate_normals(const PointCloud& cloud, const KdTree& tree,
                                              const NormalSettings& settings) {
  if (settings.k < 3)
    throw Error("normals: k must be at least 3, got " + std::to_string(settings.k));
  const Eigen::Vector3f nan = Eigen::Vector3f::Constant(std::nanf(""));
  const Eigen::Vector3d origin = cloud.sensor_origin();
  std::vector<Eigen::Vector3f> normals(cloud.size(), nan);

  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cloud.size()), [&](const auto& range) {
    std::vector<Neighbor> neighbors;  // one scratch buffer per task, never shared
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const Eigen::Vector3f& p = cloud.points[i];
      if (!is_finite(p)) continue;
      tree.knn(p, static_cast<std::size_t>(settings.k), neighbors);
      if (neighbors.size() < 3) continue;
      const PrincipalAxes pca = principal_axes(
          neighbors.size(), [&](std::size_t k) { return cloud.points[neighbors[k].index]; });
      // Two near-zero spreads mean the points lie on a line.
      if (pca.spread[1] <= 1e-12 * std::max(1.0, pca.spread[2])) continue;
      Eigen::Vector3d n = pca.axes.col(0);
      if (n.dot(origin - p.cast<double>()) < 0.0) n = -n;
      normals[i] = n.cast<float>();
    }
  });
  return normals;
}

void compute_normals(PointCloud& cloud, const NormalSettings& settings) {
  const KdTree tree(cloud);
  cloud.normals = estimate_normals(cloud, tree, settings);
}

}  // namespace lmk
