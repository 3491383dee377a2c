// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/box.h"

#include "lmk/geometry/pose.h"

namespace lmk {

bool Box::is_valid() const {
  return is_valid_pose(pose) && size.allFinite() && (size.array() > 0.0).all();
}

bool Box::contains(const Eigen::Vector3d& p) const {
  // Express p in the box frame; R^T (p - t) avoids inverting the isometry per call.
  const Eigen::Vector3d local = pose.linear().transpose() * (p - pose.translation());
  return (local.array().abs() <= 0.5 * size.array()).all();
}

std::array<Eigen::Vector3d, 8> Box::corners() const {
  std::array<Eigen::Vector3d, 8> out;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d sign((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
    out[i] = pose * (0.5 * sign.cwiseProduct(size));
  }
  return out;
}

Box Box::transformed(const Eigen::Isometry3d& T_new_frame) const {
  return Box(T_new_frame * pose, size);
}

}  // namespace lmk
