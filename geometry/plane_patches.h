// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Planar patches of an organised depth frame: square tiles of pixels whose points a plane explains,
// with the spread of the points about it. A depth camera's noise shows in that spread and nowhere
// else so cleanly: `lmk sensor-check` compares it between real and simulated frames
// (sim/sensor_validation.h), and a match's confidence measures the noise of its own frame with it
// (frame_noise.h, issue #59).

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

namespace lmk {

struct PlanePatchSettings {
  int tile = 12;  ///< patches are tile x tile pixels of the organised frame
  /// Least fraction of a tile's pixels that must hold a (kept) point.
  double min_fill = 0.75;
  /// Patches whose plane residuals a quadratic in the pixel coordinates explains beyond this
  /// fraction of their variance are not planes (an edge, a curved surface) and are skipped. Pure
  /// noise on 100 points leaves about 5%; the staircase of the depth levels on a tilted plane more.
  double max_curvature_r2 = 0.5;
};

/// One planar patch: where it is and what the sensor made of it.
struct PlanePatch {
  double depth = 0.0;          ///< mean depth along the optical axis, m
  double residual_sd = 0.0;    ///< of the residuals about the fitted plane, 3-sigma clipped, m
  double level_spacing = 0.0;  ///< median gap between consecutive distinct depths, m (NaN: < 3)
  std::size_t points = 0;
  std::vector<std::size_t> pixels;  ///< the frame's indices of its points
  Eigen::Vector4d plane;            ///< n.x + d = 0 in the sensor frame, |n| = 1
};

/// A patch's points in the sensor frame (optical: z forward), with their pixel indices.
struct PatchPoints {
  std::vector<Eigen::Vector3d> p;
  std::vector<std::size_t> pixels;
};

/// The point pixel `index` (row-major) saw, in the sensor frame, into `p_sensor`; false where it
/// saw nothing or the pixel is not to be used.
using SensorPointAt = std::function<bool(std::size_t index, Eigen::Vector3d& p_sensor)>;

/// The plane n.p + d = 0 (|n| = 1, d > 0: facing the sensor) through points in the sensor frame,
/// fitted where a depth camera's error lies: along the rays. Seen through the ray (x', y', 1) =
/// p / z, a plane is linear in inverse depth, 1/z = -(n.(x', y', 1)) / d, so a least-squares fit
/// of 1/z to (x', y', 1) gives it without the degeneracy of a principal-axes fit on a patch hardly
/// wider than its noise.
Eigen::Vector4d fit_ray_plane(const std::vector<Eigen::Vector3d>& points);

/// The statistics of `points` about `plane` (fitted to them, or to their twins).
PlanePatch measure_patch(const PatchPoints& points, const Eigen::Vector4d& plane);

/// The tile of `settings.tile` pixels a side whose top-left pixel is (u0, v0), in a frame `width`
/// pixels wide whose pixels `at` reads: the patch, when enough of its pixels hold a point and a
/// plane explains them (PlanePatchSettings); nothing otherwise. The tile must lie in the frame.
std::optional<PlanePatch> plane_patch_at(const SensorPointAt& at, int width, int u0, int v0,
                                         const PlanePatchSettings& settings = {});

}  // namespace lmk
