// SPDX-License-Identifier: BSD-3-Clause
// Plans whose motions are checked (issue #60): a step whose straight joint line sweeps the forearm
// through a box is planned around it, or, with no time to plan, refused naming the link, what it
// would touch and where; and the plan's JSON says so.

#include <gtest/gtest.h>

#include "lmk/geometry/solid.h"
#include "lmk/pbd/internal/plan_json.h"
#include "lmk/pbd/plan.h"
#include "lmk/pr2/pr2_motion_check.h"
#include "lmk/pr2/pr2_robots.h"
#include "tests/support/robot_scenes.h"

namespace lmk {
namespace {

const char* const kRight[] = {
    "r_shoulder_pan_joint", "r_shoulder_lift_joint", "r_upper_arm_roll_joint", "r_elbow_flex_joint",
    "r_forearm_roll_joint", "r_wrist_flex_joint",    "r_wrist_roll_joint"};
const char* const kLeft[] = {
    "l_shoulder_pan_joint", "l_shoulder_lift_joint", "l_upper_arm_roll_joint", "l_elbow_flex_joint",
    "l_forearm_roll_joint", "l_wrist_flex_joint",    "l_wrist_roll_joint"};

// The right arm stretched level, pointing `pan` from straight ahead; the left raised aside.
JointState arms_at(double pan) {
  JointState s;
  for (const char* j : kRight) s.names.push_back(j), s.positions.push_back(0.0);
  for (const char* j : kLeft) s.names.push_back(j), s.positions.push_back(0.0);
  s.positions[0] = pan;
  s.positions[7] = 1.5;
  s.positions[8] = -0.4;
  return s;
}

// One step: the right tool frame where it is with the arm pointing straight ahead.
Program sweep_to_straight_ahead(const Pr2Kinematics& kinematics) {
  Eigen::Isometry3d target = Eigen::Isometry3d::Identity();
  EXPECT_TRUE(kinematics.forward("right_arm", std::vector<double>(7, 0.0), target).ok());
  Program p;
  p.name = "sweep";
  ProgramStep step;
  step.right = ArmTarget{kBaseFrame, target, GripperAction::kOpen};
  p.steps.push_back(step);
  return p;
}

// A tall box in the sweep from the right (pan -1.2) to straight ahead, base frame.
PointCloud box_in_the_way() { return test::box_points({0.7, -0.45, 0.74}, {0.1, 0.1, 0.4}); }

TEST(PlanCollisions, AStepThroughABoxIsPlannedAroundItOrRefusedSayingWhere) {
  const Pr2Kinematics kinematics(RobotModel::pr2(), 0.0);
  const Program program = sweep_to_straight_ahead(kinematics);
  const PointCloud scene = box_in_the_way();
  const JointState start = arms_at(-1.2);
  PlanSettings settings;
  // Unchecked: the straight line, as before issue #60.
  const Plan blind = plan(program, {}, scene, kinematics, start, settings);
  ASSERT_TRUE(blind.valid());
  EXPECT_FALSE(blind.steps[0].arms[0].planned_around);
  EXPECT_TRUE(std::isnan(blind.steps[0].arms[0].clearance));

  // The planner's budget is its configurations checked, not the clock: a slow machine or a
  // sanitizer build plans the same path.
  Pr2MotionCheckSettings untimed;
  untimed.motion.planning_time = 1e6;
  settings.motion_checker = pr2_motion_checker(kinematics, untimed);
  const Plan around = plan(program, {}, scene, kinematics, start, settings);
  ASSERT_TRUE(around.valid()) << describe(*around.refusal);
  const PlannedArm& arm = around.steps[0].arms[0];
  EXPECT_TRUE(arm.planned_around);
  EXPECT_GE(arm.clearance, 0.02);
  EXPECT_GT(arm.trajectory.points.size(), 1u);
  // The path ends at the IK solution, and its times increase.
  for (std::size_t i = 0; i < 7; ++i)
    EXPECT_NEAR(arm.trajectory.points.back().positions[i], arm.ik.joints[i], 1e-9);
  for (std::size_t k = 1; k < arm.trajectory.points.size(); ++k)
    EXPECT_GT(arm.trajectory.points[k].time_from_start,
              arm.trajectory.points[k - 1].time_from_start);

  Pr2MotionCheckSettings no_budget = untimed;
  no_budget.motion.planning_checks = 1;
  settings.motion_checker = pr2_motion_checker(kinematics, no_budget);
  const Plan refused = plan(program, {}, scene, kinematics, start, settings);
  ASSERT_FALSE(refused.valid());
  const auto* blocked = std::get_if<Blocked>(&*refused.refusal);
  ASSERT_NE(blocked, nullptr) << describe(*refused.refusal);
  EXPECT_EQ(blocked->step, 0u);
  EXPECT_EQ(blocked->arm, Arm::kRight);
  EXPECT_EQ(blocked->contact.obstacle, "the scene");
  EXPECT_EQ(blocked->contact.link.rfind("r_", 0), 0u);
  const std::string line = describe(*refused.refusal);
  EXPECT_NE(line.find("step 0, right arm: link r_"), std::string::npos) << line;
  EXPECT_NE(line.find("m in base_link"), std::string::npos) << line;
  EXPECT_NE(line.find("no collision-free path within 1 configuration checked"), std::string::npos)
      << line;
  const nlohmann::json j = detail::plan_to_json(refused);
  EXPECT_EQ(j["refusal"]["kind"], "collision");
  EXPECT_EQ(j["refusal"]["contact"]["obstacle"], "the scene");
}

}  // namespace
}  // namespace lmk
