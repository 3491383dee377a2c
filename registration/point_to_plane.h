// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The Gauss-Newton system of point-to-plane residuals, built one correspondence at a time: ICP's
// step (icp.cpp) and the slide check's freedom of a landmark (landmark/slide_check.cpp).

#include <Eigen/Core>

namespace lmk {

/// J^T W J and J^T W r over the correspondences added, for a 6-vector of motion parameters.
struct PointToPlaneSystem {
  Eigen::Matrix<double, 6, 6> JtJ = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> Jtr = Eigen::Matrix<double, 6, 1>::Zero();

  /// One residual `r` with Jacobian `J`, weighted by `w`. Inlined by force: it runs once per
  /// correspondence, and out of line its 6x6 sum spilled to the stack on every call.
  [[gnu::always_inline]] inline void add(const Eigen::Matrix<double, 6, 1>& J, double r, double w) {
    const Eigen::Matrix<double, 6, 1> wJ = w * J;
    JtJ.noalias() += wJ * J.transpose();  // no 6x6 temporary
    Jtr.noalias() += wJ * r;
  }
};

}  // namespace lmk
