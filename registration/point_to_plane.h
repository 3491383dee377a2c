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

  /// add() for a caller that solves with a lower LDLT, which reads only JtJ's lower triangle
  /// (ICP): each column from the pair of rows that holds its diagonal, so 12 of the 18 pairs of
  /// products, and every entry on and below the diagonal summed exactly as add() sums it. The few
  /// entries above the diagonal that share a pair with one below it are summed too; the rest of
  /// the upper triangle stays zero.
  [[gnu::always_inline]] inline void add_lower(const Eigen::Matrix<double, 6, 1>& J, double r,
                                               double w) {
    const Eigen::Matrix<double, 6, 1> wJ = w * J;
    JtJ.col(0).noalias() += wJ * J(0);
    JtJ.col(1).noalias() += wJ * J(1);
    JtJ.col(2).tail<4>().noalias() += wJ.tail<4>() * J(2);
    JtJ.col(3).tail<4>().noalias() += wJ.tail<4>() * J(3);
    JtJ.col(4).tail<2>().noalias() += wJ.tail<2>() * J(4);
    JtJ.col(5).tail<2>().noalias() += wJ.tail<2>() * J(5);
    Jtr.noalias() += wJ * r;
  }
};

}  // namespace lmk
