// SPDX-License-Identifier: BSD-3-Clause
// least_axis: the spreads and the least axis of a covariance, against Eigen's iterative solver
// (slow, accurate) on patches like those the normals see, and on the degenerate ones.

#include "lmk/geometry/least_axis.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

namespace lmk {
namespace {

// The covariance of a patch with spreads `s` (increasing) along a random orthonormal frame.
Eigen::Matrix3d covariance_with(const Eigen::Vector3d& s, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  const Eigen::Quaterniond q =
      Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
  const Eigen::Matrix3d R = q.toRotationMatrix();
  return R * s.asDiagonal() * R.transpose();
}

void expect_like_iterative_solver(const Eigen::Matrix3d& c, double axis_tolerance) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> reference(c);
  const LeastAxis ours = least_axis(c);
  const double largest = reference.eigenvalues()[2];
  // The closed form's bound (least_axis.h): a double root is found to about 1e-8 of the largest.
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(ours.spread[k], reference.eigenvalues()[k], 1e-8 * largest) << c;
  }
  EXPECT_NEAR(ours.axis.norm(), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(ours.axis.dot(reference.eigenvectors().col(0))), 1.0, axis_tolerance) << c;
}

TEST(LeastAxis, PatchesOfEveryShapeMatchTheIterativeSolver) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> log_ratio(-8.0, 0.0);
  for (int trial = 0; trial < 5000; ++trial) {
    // Spreads from a flat patch's (least 1e-8 of the largest) to a round blob's, in metres^2.
    Eigen::Vector3d s(std::pow(10.0, log_ratio(rng)), std::pow(10.0, log_ratio(rng)), 1.0);
    std::sort(s.data(), s.data() + 3);
    s *= 1e-4;
    // The axis is defined to within the rounding of the covariance over the gap to the next
    // spread: only patches with a clear least spread are held to a tight axis.
    const double gap = (s[1] - s[0]) / s[2];
    expect_like_iterative_solver(covariance_with(s, rng), gap > 1e-3 ? 1e-12 : 1.0);
  }
}

TEST(LeastAxis, UnitsDoNotMatter) {
  std::mt19937 rng(3);
  const Eigen::Matrix3d c = covariance_with(Eigen::Vector3d(1e-3, 0.4, 1.0), rng);
  const LeastAxis metres = least_axis(c), kilometres = least_axis(1e-6 * c);
  EXPECT_NEAR(std::abs(metres.axis.dot(kilometres.axis)), 1.0, 1e-12);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(kilometres.spread[k] * 1e6, metres.spread[k], 1e-12);
}

TEST(LeastAxis, APlaneHasItsNormalAndAZeroSpread) {
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  const Eigen::Matrix3d c = 2.0 * u * u.transpose() + 0.5 * v * v.transpose();
  const LeastAxis ours = least_axis(c);
  EXPECT_NEAR(std::abs(ours.axis.dot(n)), 1.0, 1e-12);
  EXPECT_NEAR(ours.spread[0], 0.0, 1e-12);
  EXPECT_NEAR(ours.spread[1], 0.5, 1e-12);
  EXPECT_NEAR(ours.spread[2], 2.0, 1e-12);
}

TEST(LeastAxis, ALineHasTwoZeroSpreadsAndAnAxisAcrossIt) {
  // Points on a line: the two least spreads vanish, and any axis orthogonal to the line is least.
  for (const Eigen::Vector3d& direction : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 1),
                                           Eigen::Vector3d(1, 2, -3).normalized()}) {
    const LeastAxis ours = least_axis(3.0 * direction * direction.transpose());
    EXPECT_LE(std::abs(ours.spread[0]), 1e-8 * 3.0);
    EXPECT_LE(std::abs(ours.spread[1]), 1e-8 * 3.0);
    EXPECT_NEAR(ours.spread[2], 3.0, 1e-8 * 3.0);
    EXPECT_NEAR(ours.axis.norm(), 1.0, 1e-12);
    EXPECT_LT(std::abs(ours.axis.dot(direction)), 1e-6);
  }
}

TEST(LeastAxis, ARoundBlobAndNothingAtAll) {
  const LeastAxis blob = least_axis(0.25 * Eigen::Matrix3d::Identity());
  EXPECT_EQ(blob.spread, Eigen::Vector3d::Constant(0.25));
  EXPECT_NEAR(blob.axis.norm(), 1.0, 1e-12);
  const LeastAxis nothing = least_axis(Eigen::Matrix3d::Zero());
  EXPECT_EQ(nothing.spread, Eigen::Vector3d::Zero());
  EXPECT_NEAR(nothing.axis.norm(), 1.0, 1e-12);
}

}  // namespace
}  // namespace lmk
