// SPDX-License-Identifier: BSD-3-Clause
// Ceres refinement on the distance field: it converges from small errors and never makes the
// cost worse.

#include "lmk/registration/refine_pose.h"

#include <gtest/gtest.h>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/random.h"
#include "tests/registration/registration_fixture.h"

namespace lmk {
namespace {

TEST(RefinePose, ImprovesASmallErrorAndNeverMakesTheCostWorse) {
  const PointCloud target = test::corner_with_bump();
  const DistanceField field(target.points, {0.0025, 0.03});
  SplitMix64 rng(21);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
    const Eigen::Vector3d axis =
        Eigen::Vector3d(rng.normal(), rng.normal(), rng.normal()).normalized();
    start.linear() = Eigen::AngleAxisd(0.05 * rng.uniform01(), axis).toRotationMatrix();
    start.translation() = 0.008 * Eigen::Vector3d(rng.normal(), rng.normal(), rng.normal());
    for (RobustKernel kernel : {RobustKernel::huber, RobustKernel::cauchy, RobustKernel::tukey}) {
      RefineSettings s;
      s.loss = {kernel, 0.01};
      s.max_iterations = 30;
      const RefineResult r = refine_pose(target.points, field, start, s);
      EXPECT_LE(r.final_cost, r.initial_cost);
      if (kernel == RobustKernel::huber) {
        EXPECT_LT(r.T_target_source.translation().norm(), start.translation().norm());
      }
    }
  }
}

// The rotation's closed-form Jacobian (through SO(3)'s right Jacobian) has to be right for the
// solver to undo a rotation: translation alone would leave it.
TEST(RefinePose, UndoesARotationAboutAnyAxis) {
  const PointCloud target = test::corner_with_bump();
  const DistanceField field(target.points, {0.0025, 0.03});
  SplitMix64 rng(5);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Vector3d axis =
        Eigen::Vector3d(rng.normal(), rng.normal(), rng.normal()).normalized();
    const double angle = 0.03 + 0.03 * rng.uniform01();
    Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
    start.linear() = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    RefineSettings s;
    s.max_iterations = 30;
    const RefineResult r = refine_pose(target.points, field, start, s);
    EXPECT_LT(rotation_angle_between(r.T_target_source.linear(), Eigen::Matrix3d::Identity()),
              0.25 * angle)
        << "trial " << trial;
  }
}

TEST(RefinePose, EmptySpacePushesAwayFromOccupiedSpace) {
  // Probes placed on the surface itself: the penalty must raise the cost at the start.
  const PointCloud target = test::corner_with_bump();
  const DistanceField field(target.points, {0.0025, 0.03});
  RefineSettings with;
  with.empty_space_weight = 1.0;
  const std::vector<Eigen::Vector3f> probes(target.points.begin(), target.points.begin() + 50);
  const RefineResult a = refine_pose(target.points, field, Eigen::Isometry3d::Identity(), {});
  const RefineResult b =
      refine_pose(target.points, field, Eigen::Isometry3d::Identity(), with, probes);
  EXPECT_GT(b.initial_cost, a.initial_cost);
  EXPECT_LE(b.final_cost, b.initial_cost);
}

TEST(RefinePose, BadSettingsAreErrors) {
  const DistanceField field({{0, 0, 0}}, {0.01, 0.02});
  RefineSettings s;
  s.max_iterations = 0;
  EXPECT_THROW(refine_pose({{0, 0, 0}}, field, Eigen::Isometry3d::Identity(), s), Error);
  s = {};
  s.loss.scale = -1;
  EXPECT_THROW(refine_pose({{0, 0, 0}}, field, Eigen::Isometry3d::Identity(), s), Error);
}

}  // namespace
}  // namespace lmk
