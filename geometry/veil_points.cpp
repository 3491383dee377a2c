// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/veil_points.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <vector>

namespace lmk {

std::size_t remove_veil_points(PointCloud& cloud, double max_angle) {
  if (!cloud.is_organized() || !(max_angle > 0.0)) return 0;
  const std::size_t width = cloud.width, height = cloud.height;
  const Eigen::Vector3f origin = cloud.sensor_origin().cast<float>();
  const float cos_max = static_cast<float>(std::cos(max_angle));
  std::vector<char> veil(cloud.size(), 0);
  // Row by row in parallel: each pixel reads its neighbours and writes only its own mark.
  tbb::parallel_for(std::size_t{0}, height, [&](std::size_t v) {
    for (std::size_t u = 0; u < width; ++u) {
      const std::size_t i = v * width + u;
      const Eigen::Vector3f& p = cloud.points[i];
      if (!is_finite(p)) continue;
      const Eigen::Vector3f ray = (p - origin).normalized();
      const auto edge_on = [&](std::size_t j) {
        const Eigen::Vector3f step = cloud.points[j] - p;
        const float length = step.norm();
        return is_finite(cloud.points[j]) && length > 0.0f &&
               std::abs(step.dot(ray)) > cos_max * length;
      };
      veil[i] = (u + 1 < width && edge_on(i + 1)) || (u > 0 && edge_on(i - 1)) ||
                (v + 1 < height && edge_on(i + width)) || (v > 0 && edge_on(i - width));
    }
  });
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::size_t removed = 0;
  for (std::size_t i = 0; i < veil.size(); ++i) {
    if (!veil[i]) continue;
    cloud.points[i] = Eigen::Vector3f(nan, nan, nan);
    if (!cloud.normals.empty()) cloud.normals[i] = Eigen::Vector3f(nan, nan, nan);
    ++removed;
  }
  return removed;
}

}  // namespace lmk
