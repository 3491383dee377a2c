// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/depth_smoothing.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace lmk {

double depth_smoothing_gate(const DepthNoise& noise, double z) {
  const double z2 = z * z;
  const double level = noise.level_coefficient * z2;
  return kSmoothingGateLevels * (level > 0.0 ? level : noise.axial * z2);
}

void smooth_depth(PointCloud& cloud, int radius, const DepthNoise& noise) {
  if (!cloud.is_organized() || radius <= 0) return;
  const int width = static_cast<int>(cloud.width), height = static_cast<int>(cloud.height);
  // Depths along the optical axis (NaN: no return), computed once.
  const Eigen::Isometry3f T_sensor_cloud = cloud.T_cloud_sensor.inverse().cast<float>();
  std::vector<float> depth(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    depth[i] = is_finite(cloud.points[i]) ? (T_sensor_cloud * cloud.points[i]).z()
                                          : std::numeric_limits<float>::quiet_NaN();
  }
  const Eigen::Vector3f sensor = cloud.T_cloud_sensor.translation().cast<float>();
  tbb::parallel_for(0, height, [&](int v) {
    for (int u = 0; u < width; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * width + u;
      const float z = depth[i];
      if (!(z >= static_cast<float>(kDepthSmoothingFrom))) continue;  // near, NaN or behind
      const float gate = static_cast<float>(depth_smoothing_gate(noise, z));
      double sum = 0.0;
      int count = 0;
      for (int y = std::max(0, v - radius); y <= std::min(height - 1, v + radius); ++y) {
        const float* row = depth.data() + static_cast<std::size_t>(y) * width;
        for (int x = std::max(0, u - radius); x <= std::min(width - 1, u + radius); ++x) {
          if (std::abs(row[x] - z) <= gate) {  // false for NaN
            sum += row[x];
            ++count;
          }
        }
      }
      const float mean = static_cast<float>(sum / count);  // count >= 1: the point itself
      cloud.points[i] = sensor + (cloud.points[i] - sensor) * (mean / z);
    }
  });
}

}  // namespace lmk
