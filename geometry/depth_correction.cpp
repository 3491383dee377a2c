// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/depth_correction.h"

#include <algorithm>
#include <cmath>

#include "lmk/geometry/error.h"

namespace lmk {

int DepthCorrection::cell(int u, int v) const {
  return std::clamp(v * rows / height, 0, rows - 1) * cols +
         std::clamp(u * cols / width, 0, cols - 1);
}

double DepthCorrection::at(int u, int v) const {
  return per_metre[static_cast<std::size_t>(cell(u, v))];
}

void DepthCorrection::validate() const {
  if (width < 1 || height < 1) throw Error("depth correction: the image size must be positive");
  if (cols < 1 || rows < 1 || cols > width || rows > height) {
    throw Error("depth correction: " + std::to_string(cols) + " x " + std::to_string(rows) +
                " cells do not divide a " + std::to_string(width) + " x " + std::to_string(height) +
                " image");
  }
  if (per_metre.size() != static_cast<std::size_t>(cols) * rows) {
    throw Error("depth correction: " + std::to_string(per_metre.size()) + " values for " +
                std::to_string(cols * rows) + " cells");
  }
  for (std::size_t i = 0; i < per_metre.size(); ++i) {
    if (!std::isfinite(per_metre[i]) || std::abs(per_metre[i]) > kMaxDepthCorrection) {
      throw Error("depth correction: cell " + std::to_string(i) + "'s D " +
                  std::to_string(per_metre[i]) + " is not a finite value within +-" +
                  std::to_string(kMaxDepthCorrection) + " per metre");
    }
  }
}

void DepthCorrection::apply(PointCloud& frame) const {
  if (!frame.is_organized() || static_cast<int>(frame.width) != width ||
      static_cast<int>(frame.height) != height) {
    throw Error("depth correction: fitted on " + std::to_string(width) + " x " +
                std::to_string(height) + " images, given " +
                (frame.is_organized() ? "a frame of " + std::to_string(frame.width) + " x " +
                                            std::to_string(frame.height)
                                      : std::string("an unorganised cloud")));
  }
  // z' = z + D z^2 along the ray from the sensor: the point moves by D z times its offset from
  // the sensor, z its depth along the sensor's optical axis. Written as a displacement, a cell
  // with nothing to undo leaves its points bit for bit as they were.
  const Eigen::Vector3f origin = frame.T_cloud_sensor.translation().cast<float>();
  const Eigen::Vector3f axis = frame.T_cloud_sensor.linear().col(2).cast<float>();
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      Eigen::Vector3f& p = frame.points[static_cast<std::size_t>(v) * width + u];
      if (!is_finite(p)) continue;
      const Eigen::Vector3f ray = p - origin;
      p += ray * static_cast<float>(at(u, v) * axis.dot(ray));
    }
  }
}

}  // namespace lmk
