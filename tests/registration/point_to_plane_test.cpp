// SPDX-License-Identifier: BSD-3-Clause
// The point-to-plane system's lower-triangle sums (ICP's) against its full ones: the same bits on
// and below the diagonal, and the same step from a lower LDLT.

#include "lmk/registration/point_to_plane.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include "lmk/geometry/random.h"

namespace lmk {
namespace {

TEST(PointToPlaneSystem, TheLowerSumsAreTheFullSumsBitForBit) {
  SplitMix64 rng(12);
  PointToPlaneSystem full, lower;
  for (int n = 0; n < 500; ++n) {
    Eigen::Matrix<double, 6, 1> J;
    for (int k = 0; k < 6; ++k) J(k) = 2.0 * rng.uniform01() - 1.0;
    const double r = 0.01 * (rng.uniform01() - 0.5), w = 0.2 + rng.uniform01();
    full.add(J, r, w);
    lower.add_lower(J, r, w);
  }
  for (int col = 0; col < 6; ++col) {
    for (int row = col; row < 6; ++row) {
      EXPECT_EQ(lower.JtJ(row, col), full.JtJ(row, col)) << row << ", " << col;
    }
  }
  EXPECT_EQ(lower.Jtr, full.Jtr);
  // What ICP solves: the lower LDLT reads the lower triangle alone, so the steps are the same.
  const Eigen::Matrix<double, 6, 1> from_full = full.JtJ.ldlt().solve(-full.Jtr);
  const Eigen::Matrix<double, 6, 1> from_lower = lower.JtJ.ldlt().solve(-lower.Jtr);
  EXPECT_EQ(from_lower, from_full);
}

}  // namespace
}  // namespace lmk
