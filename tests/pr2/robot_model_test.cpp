// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pr2/robot_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/random.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

TEST(RobotModel, ShippedPr2HasTheArmsHeadAndKinect) {
  const RobotModel pr2 = RobotModel::pr2();
  EXPECT_EQ(pr2.name(), "pr2");
  for (const char* side : {"r", "l"}) {
    const KinematicChain arm =
        pr2.chain("torso_lift_link", std::string(side) + "_gripper_tool_frame");
    EXPECT_EQ(arm.dof(), 7u) << side;
    EXPECT_TRUE(arm.moving_joints()[4].continuous());  // forearm roll
    EXPECT_TRUE(arm.moving_joints()[6].continuous());  // wrist roll
  }
  EXPECT_EQ(pr2.chain("base_link", "head_mount_kinect_rgb_optical_frame").dof(),
            3u);  // torso, pan, tilt
}

TEST(RobotModel, ZeroPoseOfTheRightArmIsTheSumOfItsLinks) {
  const KinematicChain arm = RobotModel::pr2().chain("base_link", "r_gripper_tool_frame");
  std::vector<double> q(arm.dof(), 0.0);
  q[0] = 0.2;  // torso up 20 cm
  const Eigen::Isometry3d T = arm.forward(q);
  // Torso origin (-0.05, 0, 0.739675) + 0.2 up; shoulder 0.188 to the right; then 0.1 + 0.4 +
  // 0.321 + 0.18 forward along x to the tool frame.
  EXPECT_LT((T.translation() - Eigen::Vector3d(-0.05 + 1.001, -0.188, 0.939675)).norm(), 1e-12);
  EXPECT_TRUE(T.linear().isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  // Flexing the elbow by -90 degrees (about y) points the forearm and hand straight up.
  q[4] = -M_PI / 2;
  const Eigen::Vector3d p = arm.forward(q).translation();
  EXPECT_NEAR(p.x(), -0.05 + 0.1 + 0.4, 1e-12);
  EXPECT_NEAR(p.z(), 0.939675 + 0.321 + 0.18, 1e-12);
}

TEST(RobotModel, ShippedModelAgreesWithTheFullPr2Description) {
  LMK_REQUIRE_SHARED_DATA(data);
  const RobotModel ours = RobotModel::pr2();
  const RobotModel full = RobotModel::from_file((data / "robots/pr2/robot.urdf").string());
  SplitMix64 rng(7);
  for (const char* tip :
       {"r_gripper_tool_frame", "l_gripper_tool_frame", "head_mount_kinect_rgb_optical_frame"}) {
    const KinematicChain a = ours.chain("base_link", tip), b = full.chain("base_link", tip);
    ASSERT_EQ(a.dof(), b.dof()) << tip;
    for (int trial = 0; trial < 100; ++trial) {
      const std::vector<double> q = b.random_joints(rng);
      const Eigen::Isometry3d Ta = a.forward(q), Tb = b.forward(q);
      EXPECT_LT((Ta.translation() - Tb.translation()).norm(), 1e-6) << tip;
      EXPECT_LT(rotation_angle_between(Ta.linear(), Tb.linear()), 1e-6) << tip;
    }
  }
}

TEST(RobotModel, ClearErrors) {
  const RobotModel pr2 = RobotModel::pr2();
  EXPECT_THROW(pr2.chain("base_link", "no_such_link"), Error);
  EXPECT_THROW(pr2.chain("r_gripper_tool_frame", "base_link"), Error);  // not a descendant
  EXPECT_THROW(pr2.chain("base_link", "r_gripper_tool_frame").forward({0.0, 1.0}), Error);
  test::ScratchDir dir;
  EXPECT_THROW(RobotModel::from_file(dir.file("missing.urdf")), Error);
  test::write_text(dir.file("bad.urdf"),
                   "<robot name='x'><joint name='j' type='revolute'/></robot>");
  EXPECT_THROW(RobotModel::from_file(dir.file("bad.urdf")), Error);
}

}  // namespace
}  // namespace lmk
