// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A simulated Kinect v1 (docs/datasets.md, "The simulated Kinect"): a 640x480 pinhole camera that
// ray-casts a triangle mesh with CGAL's AABB tree and degrades the depth as the real sensor does.

#include <cstdint>
#include <vector>

#include "lmk/geometry/point_cloud.h"
#include "lmk/sim/mesh.h"

namespace lmk {

struct DepthSensorSettings {
  int width = 640;
  int height = 480;
  double fx = 525.0, fy = 525.0;  ///< focal lengths of the registered image, pixels
  double cx = 319.5, cy = 239.5;  ///< principal point, pixels
  double min_range = 0.5;         ///< no return nearer than this depth, m
  double max_range = 4.0;         ///< no return beyond this depth, m
  /// No return where the ray meets the surface more obliquely than this (radians from the normal).
  double max_incidence = 75.0 * M_PI / 180.0;
  /// Axial noise, disparity quantisation and millimetre depth; false renders exact depth (and no
  /// flying pixels).
  bool noise = true;
  /// Axial noise sigma(z) = noise_a + noise_b (z - noise_z0)^2, metres, before the quantisation.
  /// 0.0013 z^2 is a disparity noise of 0.057 px, fitted to the planes of 51 real Kinect frames
  /// (`lmk sensor-check`; why not a published model: docs/datasets.md, "The simulated Kinect").
  double noise_a = 0.0, noise_b = 0.0013, noise_z0 = 0.0;
  /// Disparity: the IR camera (focal length disparity_focal, about 580 px, not the colour image's
  /// 525) sees the projector's pattern over the baseline, in steps of disparity_step pixels, so
  /// depth comes in levels z^2 step / (f b) apart: 2.9 mm at 1 m, 18 mm at 2.5 m.
  double baseline = 0.075;            ///< projector-camera baseline, m
  double disparity_focal = 580.0;     ///< pixels
  double disparity_step = 1.0 / 8.0;  ///< pixels; 0: no disparity (a time-of-flight camera)
  /// The driver reports whole millimetres (OpenNI's depth image); 0 keeps depth continuous.
  double depth_unit = 0.001;
  /// No return where the projector, `baseline` along the sensor's +x, cannot light the surface:
  /// the shadow beside each object's left edge (as the image shows it) on what lies behind.
  bool shadows = true;
  /// At a depth edge (neighbouring depths differing by more than edge_jump of the depth), a pixel
  /// sees both surfaces and returns a depth between them with this probability: a flying pixel.
  /// 2% gives the real frames' share of mixed returns at depth edges (1.8%, lmk sensor-check).
  double flying_pixel_rate = 0.02;
  double edge_jump = 0.03;
  /// The noise of neighbouring pixels is correlated over blocks of this many pixels a side (odd):
  /// the sensor finds each pixel's disparity by matching a window of the projected pattern.
  int noise_window = 1;
  std::uint64_t seed = 0;  ///< noise seed; each pixel has its own stream
  /// A painted mesh (TriangleMesh::colours) gives each point its surface's colour, shaded by how
  /// squarely the light meets it, times this gain per channel (r, g, b): the light's brightness
  /// and tint, as a scene's lamps or a camera's white balance change them.
  Eigen::Vector3d light = Eigen::Vector3d::Ones();
  /// Colour noise, 8-bit counts (sigma per channel): a Kinect's colour camera's, roughly.
  double colour_noise = 2.0;
};

/// The frame's noise: one unit-variance normal per pixel (width x height, row-major), averaged over
/// noise_window blocks and rescaled to unit variance. Deterministic in settings.seed.
std::vector<double> sensor_noise_field(const DepthSensorSettings& settings);

/// The depth the sensor reports for a surface at true depth `z` (m) given the pixel's unit noise
/// (from sensor_noise_field): Gaussian axial noise sigma(z) times it, then the disparity's
/// quantisation, then the driver's millimetres.
double sensor_depth(double z, double unit_noise, const DepthSensorSettings& settings);

/// The spacing of the depth levels at depth `z`: disparity_step z^2 / (disparity_focal baseline).
double depth_level_spacing(double z, const DepthSensorSettings& settings);

/// Renders `world` seen from T_world_sensor (optical frame: z forward, x right, y down). Returns an
/// organised width x height cloud in the world frame, NaN where there is no return, with
/// T_cloud_sensor = T_world_sensor, and colours registered to it when `world` is painted.
/// Deterministic for a given seed whatever the thread count.
PointCloud render_depth(const TriangleMesh& world, const Eigen::Isometry3d& T_world_sensor,
                        const DepthSensorSettings& settings = {});

}  // namespace lmk
