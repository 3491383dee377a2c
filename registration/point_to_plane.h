// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The Gauss-Newton system of point-to-plane residuals, built one correspondence at a time: ICP's
// step (icp.cpp) and the slide check's freedom of a landmark (landmark/slide_check.cpp).

#include <Eigen/Core>

namespace lmk {

/// J^T W J and J^T W r over the correspondences added, for a 6-vector of motion parameters.
class PointToPlaneSystem {
 public:
  /// One residual `r` with Jacobian `J`, weighted by `w`. Inlined by force: it runs once per
  /// correspondence, and out of line its 6x6 sum spilled to the stack on every call. Only the
  /// lower triangle of J^T W J is summed (21 of its 36 products): its entries are those the full
  /// outer product gave, and the solvers read no other.
  [[gnu::always_inline]] inline void add(const Eigen::Matrix<double, 6, 1>& J, double r, double w) {
    const Eigen::Matrix<double, 6, 1> wJ = w * J;
    lower_.col(0) += wJ * J(0);
    lower_.col(1).tail<5>() += wJ.tail<5>() * J(1);
    lower_.col(2).tail<4>() += wJ.tail<4>() * J(2);
    lower_.col(3).tail<3>() += wJ.tail<3>() * J(3);
    lower_.col(4).tail<2>() += wJ.tail<2>() * J(4);
    lower_(5, 5) += wJ(5) * J(5);
    Jtr_.noalias() += wJ * r;
  }

  /// J^T W J, symmetric: its lower triangle mirrored.
  Eigen::Matrix<double, 6, 6> JtJ() const { return lower_.selfadjointView<Eigen::Lower>(); }
  const Eigen::Matrix<double, 6, 1>& Jtr() const { return Jtr_; }

 private:
  Eigen::Matrix<double, 6, 6> lower_ = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> Jtr_ = Eigen::Matrix<double, 6, 1>::Zero();
};

}  // namespace lmk
