// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pr2/ik_solver.h"

#include <gtest/gtest.h>

#include "lmk/geometry/pose.h"
#include "lmk/geometry/random.h"

namespace lmk {
namespace {

void expect_within_limits(const KinematicChain& chain, const std::vector<double>& q) {
  const auto joints = chain.moving_joints();
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (joints[i].continuous()) {
      EXPECT_LE(std::abs(q[i]), M_PI + 1e-12) << joints[i].name;
    } else {
      EXPECT_GE(q[i], joints[i].lower) << joints[i].name;
      EXPECT_LE(q[i], joints[i].upper) << joints[i].name;
    }
  }
}

TEST(IkSolver, SolvesRandomReachableTargetsForBothArms) {
  const RobotModel pr2 = RobotModel::pr2();
  SplitMix64 rng(2024);
  for (const char* tip : {"r_gripper_tool_frame", "l_gripper_tool_frame"}) {
    const KinematicChain arm = pr2.chain("torso_lift_link", tip);
    int solved = 0;
    const int trials = 500;
    for (int t = 0; t < trials; ++t) {
      // A reachable target: FK of random joints within limits. IK starts from another random seed.
      const Eigen::Isometry3d target = arm.forward(arm.random_joints(rng));
      const IkResult r = solve_ik(arm, target, arm.random_joints(rng));
      if (!r.success) continue;
      ++solved;
      const Eigen::Isometry3d reached = arm.forward(r.joints);
      EXPECT_LE((reached.translation() - target.translation()).norm(), 0.001);
      EXPECT_LE(rotation_angle_between(reached.linear(), target.linear()), 0.5 * M_PI / 180.0);
      expect_within_limits(arm, r.joints);
    }
    EXPECT_GE(solved, trials * 99 / 100) << tip;
  }
}

TEST(IkSolver, PrefersTheSolutionAtTheSeed) {
  const KinematicChain arm = RobotModel::pr2().chain("torso_lift_link", "r_gripper_tool_frame");
  const std::vector<double> q = {-0.5, 0.3, -1.0, -1.2, 0.4, -0.8, 1.0};
  const IkResult r = solve_ik(arm, arm.forward(q), q);
  ASSERT_TRUE(r.success);
  for (std::size_t i = 0; i < q.size(); ++i) EXPECT_NEAR(r.joints[i], q[i], 1e-6);
}

TEST(IkSolver, FarTargetsAreOutOfTheWorkspace) {
  const KinematicChain arm = RobotModel::pr2().chain("torso_lift_link", "r_gripper_tool_frame");
  SplitMix64 rng(3);
  for (int t = 0; t < 20; ++t) {
    const Eigen::Vector3d direction =
        Eigen::Vector3d(rng.normal(), rng.normal(), rng.normal()).normalized();
    Eigen::Isometry3d target = Eigen::Isometry3d::Identity();
    target.translation() = 2.0 * direction;
    const IkResult r = solve_ik(arm, target, {});
    EXPECT_FALSE(r.success);
    EXPECT_EQ(r.failure, IkFailure::kOutOfWorkspace);
    EXPECT_NE(r.message.find("out of the workspace"), std::string::npos) << r.message;
  }
}

TEST(IkSolver, JointLimitFailuresSaySo) {
  const KinematicChain arm = RobotModel::pr2().chain("torso_lift_link", "r_gripper_tool_frame");
  // The right arm's shoulder pan stops at +0.71 rad: the tool straight out to the robot's left,
  // level with the shoulder, needs about +1.57 rad.
  std::vector<double> q(7, 0.0);
  q[0] = M_PI / 2;
  const IkResult r = solve_ik(arm, arm.forward(q), {});
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.failure, IkFailure::kJointLimits) << r.message;
}

TEST(IkSolver, BadRequests) {
  const KinematicChain arm = RobotModel::pr2().chain("torso_lift_link", "r_gripper_tool_frame");
  EXPECT_EQ(solve_ik(arm, Eigen::Isometry3d::Identity(), {0.0, 1.0}).failure,
            IkFailure::kBadRequest);
  Eigen::Isometry3d nan = Eigen::Isometry3d::Identity();
  nan.translation().x() = std::nan("");
  EXPECT_EQ(solve_ik(arm, nan, {}).failure, IkFailure::kBadRequest);
}

}  // namespace
}  // namespace lmk
