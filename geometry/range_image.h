// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What a scene's sensor saw along each of its rays: the depth image behind projective visibility
// (issue #16, part 3). A point placed in the scene by a candidate pose is seen when the image holds
// a surface at its depth, hidden when the surface lies clearly in front of it, and seen through
// when the sensor measured a surface clearly behind it.

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

#include "lmk/geometry/pinhole_intrinsics.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk {

/// Pixels of error beyond which an organised cloud's fitted intrinsics say it is no pinhole view
/// from its recorded pose (RangeImage::from_cloud).
inline constexpr double kMaxIntrinsicsFitRms = 0.5;

class RangeImage {
 public:
  /// The image of `cloud` seen from its sensor (cloud.T_cloud_sensor).
  ///
  /// - An organised cloud is its own image: its intrinsics are fitted to its pixels (least squares
  ///   of u against x/z and v against y/z in the sensor frame). When the fit leaves more than
  ///   `max_fit_rms` pixels of error, the pixels are no pinhole view from the recorded pose (a
  ///   wrong VIEWPOINT, a cloud moved without its pose), and there is no image.
  /// - An unorganised cloud is projected through `fallback` into a depth buffer that keeps the
  ///   nearest point per pixel.
  /// Nothing for a cloud without a point in front of its sensor.
  ///
  /// `known`: the intrinsics of an organised cloud's camera when already fitted, to a frame of the
  /// same size from the same camera (a tracker's stream): the fit is skipped, half of the work,
  /// when they project its pixels within `max_fit_rms`; fitted as usual otherwise.
  static std::optional<RangeImage> from_cloud(const PointCloud& cloud,
                                              const PinholeIntrinsics& fallback = {},
                                              double max_fit_rms = kMaxIntrinsicsFitRms,
                                              const PinholeIntrinsics* known = nullptr);

  /// What the sensor saw along the ray through `point` (cloud frame).
  struct Look {
    bool in_view = false;  ///< in front of the sensor and inside the image
    double depth = 0.0;    ///< the point's own depth along the optical axis, m
    /// The depth the sensor measured at its pixel, m; NaN where it measured nothing.
    double measured = 0.0;
    std::size_t pixel = 0;  ///< the row-major index of its pixel, when in view
  };
  Look look(const Eigen::Vector3f& point) const;

  /// The pixel coordinates (u right, v down) `point` projects to, if it lies in front of the
  /// sensor; possibly outside the image.
  std::optional<Eigen::Vector2d> project(const Eigen::Vector3f& point) const;

  /// The sensor's distance to `point` along its optical axis, m (negative behind it).
  double depth_of(const Eigen::Vector3f& point) const;

  const PinholeIntrinsics& intrinsics() const { return k_; }
  bool organised() const { return organised_; }
  /// Depth per pixel, row-major, NaN where nothing was measured.
  const std::vector<float>& depths() const { return depth_; }
  /// Colour per pixel, row-major, where the cloud has colour (registered RGB); else empty.
  const std::vector<Color>& colours() const { return colour_; }

 private:
  /// The index of the pixel a point in the sensor frame falls in, if in front and in the image.
  std::optional<std::size_t> pixel_of(const Eigen::Vector3f& p_sensor) const;

  PinholeIntrinsics k_;
  Eigen::Isometry3f T_sensor_cloud_ = Eigen::Isometry3f::Identity();
  std::vector<float> depth_;
  std::vector<Color> colour_;
  bool organised_ = false;
};

}  // namespace lmk
