// SPDX-License-Identifier: BSD-3-Clause
// Approach and retreat along the gripper's axis (approach.h, issue #60): a grasp is reached from
// 10 cm back along the tool's x axis with the fingers open, a release backs off the same way, and
// a program that demonstrates its own approach or retreat gains none.

#include "lmk/pbd/approach.h"

#include <gtest/gtest.h>

#include "lmk/geometry/pose.h"

namespace lmk {
namespace {

// A gripper pointing down (x along -z) at `p`, base frame.
Eigen::Isometry3d down_at(const Eigen::Vector3d& p) {
  return pose_from_xyz_rpy(p, {0, 0.5 * M_PI, 0});
}

ProgramStep right(const Eigen::Isometry3d& T, GripperAction gripper) {
  ProgramStep s;
  s.right = ArmTarget{kBaseFrame, T, gripper};
  return s;
}

std::vector<StepMotion> motions(const Program& p, std::size_t s, double distance = 0.1) {
  return step_motions(p, s, distance, [](const ArmTarget& t) { return t.T_frame_ee; });
}

const Eigen::Vector3d kCup(0.6, -0.2, 0.8);

TEST(Approach, AGraspFromAsideIsApproachedAlongTheGrippersAxisWithTheFingersOpen) {
  Program p;
  p.steps = {right(down_at({0.4, -0.5, 1.0}), GripperAction::kOpen),
             right(down_at(kCup), GripperAction::kClose)};
  const std::vector<StepMotion> m = motions(p, 1);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].phase, Phase::kApproach);
  EXPECT_EQ(m[1].phase, Phase::kTarget);
  ASSERT_EQ(m[0].goals.size(), 1u);
  const ArmGoal& pre = m[0].goals[0];
  EXPECT_EQ(pre.arm, Arm::kRight);
  EXPECT_EQ(pre.gripper, GripperAction::kOpen);
  // Pointing down, the axis is -z: the pre-grasp is 10 cm above, the hand turned the same way.
  EXPECT_LT((pre.T_base_ee.translation() - (kCup + Eigen::Vector3d(0, 0, 0.1))).norm(), 1e-12);
  EXPECT_TRUE(pre.T_base_ee.linear().isApprox(down_at(kCup).linear(), 1e-12));
  EXPECT_EQ(m[1].goals[0].gripper, GripperAction::kClose);
  EXPECT_STREQ(phase_name(m[0].phase), "approach");
}

TEST(Approach, ADemonstratedApproachGainsNone) {
  Program p;
  // 8 cm above, a centimetre off the axis and 5 degrees turned: a hand-guided pre-grasp.
  Eigen::Isometry3d pre = down_at(kCup + Eigen::Vector3d(0.01, 0, 0.08));
  pre.linear() = pre.linear() * Eigen::AngleAxisd(5.0 * M_PI / 180.0, Eigen::Vector3d::UnitX());
  p.steps = {right(pre, GripperAction::kOpen), right(down_at(kCup), GripperAction::kClose)};
  EXPECT_EQ(motions(p, 1).size(), 1u);
  // From beside the cup at the same height, it is no approach.
  p.steps[0] = right(down_at(kCup + Eigen::Vector3d(0.08, 0, 0)), GripperAction::kOpen);
  EXPECT_EQ(motions(p, 1).size(), 2u);
  // Nor from above but turned a quarter round the vertical.
  p.steps[0] = right(down_at(kCup + Eigen::Vector3d(0, 0, 0.1)) *
                         Eigen::AngleAxisd(0.5 * M_PI, Eigen::Vector3d::UnitX()),
                     GripperAction::kOpen);
  EXPECT_EQ(motions(p, 1).size(), 2u);
}

TEST(Approach, AReleaseBacksOffUnlessTheNextStepDoes) {
  Program p;
  p.steps = {right(down_at({0.4, -0.5, 1.0}), GripperAction::kClose),
             right(down_at(kCup), GripperAction::kOpen)};
  std::vector<StepMotion> m = motions(p, 1);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].phase, Phase::kTarget);
  EXPECT_EQ(m[1].phase, Phase::kRetreat);
  EXPECT_LT((m[1].goals[0].T_base_ee.translation() - (kCup + Eigen::Vector3d(0, 0, 0.1))).norm(),
            1e-12);
  EXPECT_EQ(m[1].goals[0].gripper, GripperAction::kOpen);
  // A next step straight up out of the cup is the retreat.
  p.steps.push_back(right(down_at(kCup + Eigen::Vector3d(0, 0, 0.15)), GripperAction::kOpen));
  EXPECT_EQ(motions(p, 1).size(), 1u);
}

TEST(Approach, NeitherForAnArmsFirstStepAnUnchangedGripperOrNoDistance) {
  Program p;
  p.steps = {right(down_at(kCup), GripperAction::kClose),
             right(down_at(kCup + Eigen::Vector3d(0, 0, 0.3)), GripperAction::kClose)};
  EXPECT_EQ(motions(p, 0).size(), 1u);  // how the fingers stood before is not known
  EXPECT_EQ(motions(p, 1).size(), 1u);  // closed, and still closed: no grasp
  p.steps[0].right->gripper = GripperAction::kOpen;
  p.steps[0].right->T_frame_ee = down_at({0.4, -0.5, 1.0});
  EXPECT_EQ(motions(p, 1).size(), 2u);
  EXPECT_EQ(motions(p, 1, 0.0).size(), 1u);
}

TEST(Approach, OnlyTheArmThatGraspsApproaches) {
  // Steps for the left arm in between count as its own, not the right's.
  Program p;
  ProgramStep both = right(down_at(kCup), GripperAction::kClose);
  both.left = ArmTarget{kBaseFrame, down_at({0.5, 0.4, 1.0}), GripperAction::kOpen};
  ProgramStep left_only;
  left_only.left = ArmTarget{kBaseFrame, down_at({0.5, 0.5, 1.0}), GripperAction::kClose};
  p.steps = {right(down_at({0.4, -0.5, 1.0}), GripperAction::kOpen), left_only, both};
  const std::vector<StepMotion> m = motions(p, 2);
  ASSERT_EQ(m.size(), 3u);  // the right's approach; both targets; the left's release backing off
  ASSERT_EQ(m[0].goals.size(), 1u);
  EXPECT_EQ(m[0].goals[0].arm, Arm::kRight);
  EXPECT_EQ(m[1].goals.size(), 2u);
  ASSERT_EQ(m[2].goals.size(), 1u);
  EXPECT_EQ(m[2].goals[0].arm, Arm::kLeft);
  EXPECT_EQ(m[2].phase, Phase::kRetreat);
}

}  // namespace
}  // namespace lmk
