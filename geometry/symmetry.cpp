// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/symmetry.h"

#include <cmath>

#include "lmk/geometry/pose.h"

namespace lmk {

Eigen::Matrix3d nearest_symmetric_rotation(const Eigen::Matrix3d& R,
                                           const Eigen::Matrix3d& R_reference,
                                           const Symmetry& symmetry) {
  if (!symmetry.axis || symmetry.axis->norm() == 0.0) return R;
  const Eigen::Vector3d a = symmetry.axis->normalized();
  if (symmetry.order == 0) {
    // The twist of q = R^T R_reference about a is the quaternion (w, (v.a) a), normalised: the
    // turn about a that takes R closest to R_reference.
    const Eigen::Quaterniond q(R.transpose() * R_reference);
    const double twist = 2.0 * std::atan2(q.vec().dot(a), q.w());
    return R * Eigen::AngleAxisd(twist, a).matrix();
  }
  Eigen::Matrix3d best = R;
  double best_angle = rotation_angle_between(R, R_reference);
  for (int k = 1; k < symmetry.order; ++k) {
    const Eigen::Matrix3d turned =
        R * Eigen::AngleAxisd(2.0 * M_PI * k / symmetry.order, a).matrix();
    const double angle = rotation_angle_between(turned, R_reference);
    if (angle < best_angle) {
      best_angle = angle;
      best = turned;
    }
  }
  return best;
}

}  // namespace lmk
