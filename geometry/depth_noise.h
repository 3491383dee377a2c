// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The expected depth error of a structured-light sensor at a given depth (Kinect v1 by default):
// the unit in which the sensor-aware metric measures residuals (issue #16, part 3), so that one
// threshold holds from 0.5 m to 3.5 m.

#include <cmath>

namespace lmk {

struct DepthNoise {
  /// Axial noise coefficient: sigma = axial z^2 (m^-1). 0.0013 is what `lmk sensor-check` fitted
  /// to 51 real Kinect frames (docs/datasets.md).
  double axial = 0.0013;
  /// Disparity quantisation: depth levels disparity_step z^2 / (focal baseline) apart, whose
  /// rounding adds a uniform error of spacing / sqrt(12). 0 for a sensor without it.
  double level_coefficient = (1.0 / 8.0) / (580.0 * 0.075);
  /// What remains at any depth: voxel averaging, the landmark's own resolution and the pose error
  /// of a true match, m.
  double floor = 0.002;

  /// One depth measurement's standard deviation at depth z (m), without the floor.
  double measurement_sigma(double z) const {
    const double z2 = z * z;
    const double level = level_coefficient * z2 / std::sqrt(12.0);
    return std::sqrt(axial * z2 * axial * z2 + level * level);
  }

  /// `measured` (one measurement's sigma a frame measured itself, geometry/frame_noise.h) where it
  /// is finite, else this model's at depth z.
  double measurement_sigma_or(double measured, double z) const {
    return std::isfinite(measured) ? measured : measurement_sigma(z);
  }

  /// The standard deviation of a residual between two measurements of sigma `a` and `b` (a
  /// landmark point's at capture and a scene surface's): both errors and the floor.
  double residual_of(double a, double b) const { return std::sqrt(a * a + b * b + floor * floor); }

  /// residual_of() with this model's sigmas for a landmark point captured at depth z_capture and a
  /// scene surface measured at depth z_scene.
  double residual_sigma(double z_capture, double z_scene) const {
    return residual_of(measurement_sigma(z_capture), measurement_sigma(z_scene));
  }
};

}  // namespace lmk
