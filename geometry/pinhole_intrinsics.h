// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The pinhole model of a depth camera.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>

namespace lmk {

/// A pinhole model's intrinsics, pixels: pixel (u, v) with depth z back-projects to
/// x = (u - cx) z / fx, y = (v - cy) z / fy in the optical frame (x right, y down, z forward).
/// The defaults are the Kinect v1's.
struct PinholeIntrinsics {
  double fx = 525.0, fy = 525.0, cx = 319.5, cy = 239.5;
  int width = 640, height = 480;

  /// Throws lmk::Error naming `what` unless the focal lengths are positive and every value finite.
  void validate(const std::string& what) const;

  /// The row-major index, in a width x height image, of the pixel nearest to where `p` (optical
  /// frame) projects; nothing when `p` is not finite, not in front of the camera, or falls outside
  /// the image.
  std::optional<std::size_t> pixel_of(const Eigen::Vector3d& p, int width, int height) const;
};

}  // namespace lmk
