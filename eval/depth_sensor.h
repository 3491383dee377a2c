#pragma once
// A simulated Kinect v1 (DESIGN.md, "Simulated sensor"): a 640x480 pinhole camera that ray-casts
// a triangle mesh with CGAL's AABB tree and degrades the depth as the real sensor does.

#include <cstdint>

#include "eval/mesh.h"
#include "geometry/point_cloud.h"

namespace lmk {

struct DepthSensorSettings {
  int width = 640;
  int height = 480;
  double fx = 525.0, fy = 525.0;  ///< focal lengths, pixels
  double cx = 319.5, cy = 239.5;  ///< principal point, pixels
  double min_range = 0.5;         ///< no return nearer than this depth, m
  double max_range = 4.0;         ///< no return beyond this depth, m
  /// No return where the ray meets the surface more obliquely than this (radians from the normal).
  double max_incidence = 75.0 * M_PI / 180.0;
  bool noise = true;  ///< axial noise and disparity quantisation; false renders exact depth
  /// Axial noise sigma(z) = noise_a + noise_b (z - noise_z0)^2, metres.
  double noise_a = 0.0012, noise_b = 0.0019, noise_z0 = 0.4;
  double baseline = 0.075;            ///< projector-camera baseline, m
  double disparity_step = 1.0 / 8.0;  ///< disparity quantisation, pixels
  std::uint64_t seed = 0;             ///< noise seed; each pixel has its own stream
};

/// Renders `world` seen from T_world_sensor (optical frame: z forward, x right, y down). Returns an
/// organised width x height cloud in the world frame, NaN where there is no return, with
/// T_cloud_sensor = T_world_sensor. Deterministic for a given seed whatever the thread count.
PointCloud render_depth(const TriangleMesh& world, const Eigen::Isometry3d& T_world_sensor,
                        const DepthSensorSettings& settings = {});

}  // namespace lmk
