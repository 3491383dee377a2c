// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/projector_shadow.h"

#include <cmath>

namespace lmk {

std::vector<ShadowRay> projector_shadow_rays(const PointCloud& cloud,
                                             const ProjectorShadowSettings& s) {
  std::vector<ShadowRay> ends;
  if (cloud.height <= 1 || cloud.points.size() != std::size_t{cloud.width} * cloud.height ||
      !(s.baseline > 0.0))
    return ends;
  const Eigen::Isometry3d T_sensor_cloud = cloud.T_cloud_sensor.inverse();
  const auto in_sensor = [&](std::size_t i) -> Eigen::Vector3d {
    return T_sensor_cloud * cloud.points[i].cast<double>();
  };
  for (std::uint32_t v = 0; v < cloud.height; ++v) {
    const std::size_t row = std::size_t{v} * cloud.width;
    std::uint32_t u = 0;
    while (u < cloud.width) {
      if (is_finite(cloud.points[row + u])) {
        ++u;
        continue;
      }
      const std::uint32_t first = u;  // a strip of no returns: [first, u)
      while (u < cloud.width && !is_finite(cloud.points[row + u])) ++u;
      if (first == 0 || u == cloud.width) continue;
      const Eigen::Vector3d left = in_sensor(row + first - 1), right = in_sensor(row + u);
      if (!(left.z() > 0.0 && right.z() > 0.0)) continue;
      // Farther on the left, nearer on the right: the shadow of the right-hand surface.
      if (left.z() < s.min_depth_ratio * right.z()) continue;
      // Normalised image coordinates of the strip's neighbours; one pixel is their gap over the
      // pixels between them (a pinhole camera is linear in them).
      const Eigen::Vector2d a = left.head<2>() / left.z(), b = right.head<2>() / right.z();
      const double pixel = (b.x() - a.x()) / static_cast<double>(u - first + 1);
      if (!(pixel > 0.0)) continue;
      const double expected = s.baseline * (1.0 / right.z() - 1.0 / left.z()) / pixel;
      const double strip = static_cast<double>(u - first);
      if (std::abs(strip - expected) > s.width_tolerance) continue;
      for (std::uint32_t k = first; k < u; ++k) {
        const double t = static_cast<double>(k - first + 1) / static_cast<double>(u - first + 1);
        const Eigen::Vector2d ray = a + t * (b - a);
        // The ray is lit, so free, until it enters the shadow volume behind the edge: there the
        // projector's view of it, x' - B/z, reaches the edge's, x'_edge - B/z_edge. Its surface is
        // unlit, so it lies beyond that depth (at most the far side's).
        const double lit = s.baseline / right.z() - (b.x() - ray.x());
        const double depth = lit > s.baseline / left.z() ? s.baseline / lit : left.z();
        const Eigen::Vector3d end = Eigen::Vector3d(ray.x(), ray.y(), 1.0) * depth;
        ends.push_back({row + k, (cloud.T_cloud_sensor * end).cast<float>()});
      }
    }
  }
  return ends;
}

std::vector<Eigen::Vector3f> projector_shadow_ray_ends(const PointCloud& cloud,
                                                       const ProjectorShadowSettings& settings) {
  std::vector<Eigen::Vector3f> ends;
  for (const ShadowRay& ray : projector_shadow_rays(cloud, settings)) ends.push_back(ray.end);
  return ends;
}

}  // namespace lmk
