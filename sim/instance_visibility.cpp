// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/sim/instance_visibility.h"

#include <algorithm>
#include <cmath>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/random.h"

namespace lmk {

std::vector<Eigen::Vector3d> points_on_instance(const Landmark& landmark, const Box& instance) {
  const Eigen::Isometry3d T_world_capture = instance.pose * landmark.box.pose.inverse();
  std::vector<Eigen::Vector3d> out;
  out.reserve(landmark.points.size());
  for (const Eigen::Vector3f& q : landmark.points.points)
    out.push_back(T_world_capture * q.cast<double>());
  return out;
}

std::vector<char> seen_on_instance(const Landmark& landmark, const Box& instance,
                                   const PointCloud& exact, const DepthSensorSettings& s,
                                   double tolerance) {
  if (exact.width != static_cast<std::uint32_t>(s.width) ||
      exact.height != static_cast<std::uint32_t>(s.height))
    throw Error("seen_on_instance: the frame is not the sensor's size");
  const Eigen::Isometry3d T_sensor_world = exact.T_cloud_sensor.inverse();
  std::vector<char> seen;
  seen.reserve(landmark.points.size());
  for (const Eigen::Vector3d& world : points_on_instance(landmark, instance)) {
    const Eigen::Vector3d p = T_sensor_world * world;
    seen.push_back(0);
    if (!(p.z() > 0.0)) continue;
    const long u = std::lround(s.fx * p.x() / p.z() + s.cx);
    const long v = std::lround(s.fy * p.y() / p.z() + s.cy);
    if (u < 0 || v < 0 || u >= s.width || v >= s.height) continue;
    const Eigen::Vector3f& hit = exact.points[static_cast<std::size_t>(v) * s.width + u];
    if (!is_finite(hit)) continue;
    seen.back() = std::abs((T_sensor_world * hit.cast<double>()).z() - p.z()) <= tolerance;
  }
  return seen;
}

double hidden_fraction(const Landmark& landmark, const Box& instance, const PointCloud& exact,
                       const DepthSensorSettings& s, double tolerance) {
  const std::vector<char> seen = seen_on_instance(landmark, instance, exact, s, tolerance);
  if (seen.empty()) return 0.0;
  return 1.0 - static_cast<double>(std::count(seen.begin(), seen.end(), 1)) /
                   static_cast<double>(seen.size());
}

Eigen::Isometry3d random_viewpoint(const Eigen::Vector3d& target, const Eigen::Vector3d& reference,
                                   std::uint64_t seed, const ViewpointRange& r) {
  if (!(r.min_range > 0.0 && r.max_range >= r.min_range && r.max_azimuth >= 0.0 &&
        r.max_height >= r.min_height))
    throw Error("random_viewpoint: the ranges must be ordered and the distances positive");
  SplitMix64 rng(seed);
  const double distance = r.min_range + (r.max_range - r.min_range) * rng.uniform01();
  const double azimuth = r.max_azimuth * (2.0 * rng.uniform01() - 1.0);
  const double height = r.min_height + (r.max_height - r.min_height) * rng.uniform01();
  Eigen::Vector3d back = reference - target;  // horizontal, towards the demonstration
  back.z() = 0.0;
  if (back.norm() < 1e-9) back = -Eigen::Vector3d::UnitY();
  back = Eigen::AngleAxisd(azimuth, Eigen::Vector3d::UnitZ()) * back.normalized();
  // Never steeper than 70 degrees: looking straight down, "up" in the image is undefined.
  const double max_rise = distance * std::sin(70.0 * M_PI / 180.0);
  const double rise = std::clamp(height - target.z(), -max_rise, max_rise);
  const Eigen::Vector3d eye = target + back * std::sqrt(distance * distance - rise * rise) +
                              Eigen::Vector3d(0.0, 0.0, rise);
  return camera_look_at(eye, target, Eigen::Vector3d::UnitZ());
}

}  // namespace lmk
