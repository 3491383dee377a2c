// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pr2/simulated_pr2.h"

#include <gtest/gtest.h>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/pr2/pr2_robots.h"
#include "tests/support/lifecycle_conformance.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

class SimulatedPr2Test : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(robot_.configure().ok());
    ASSERT_TRUE(robot_.activate().ok());
    arm_ = *robot_.kinematics().group("right_arm");
  }
  JointTrajectory trajectory(const std::vector<std::vector<double>>& points, double step) const {
    JointTrajectory t;
    for (const JointInfo& j : arm_.joints) t.joint_names.push_back(j.name);
    for (std::size_t i = 0; i < points.size(); ++i) t.points.push_back({points[i], step * (i + 1)});
    return t;
  }
  SimulatedPr2 robot_;
  GroupInfo arm_;
};

const std::vector<double> kTarget = {-0.5, 0.3, -1.0, -1.2, 0.4, -0.8, 1.0};

TEST_F(SimulatedPr2Test, ExecutesAValidTrajectoryToItsFinalState) {
  ASSERT_TRUE(
      robot_
          .send_trajectory("right_arm",
                           trajectory({{-0.25, 0.15, -0.5, -0.6, 0.2, -0.4, 0.5}, kTarget}, 2.0))
          .ok());
  EXPECT_EQ(robot_.group_positions("right_arm"), kTarget);
  ASSERT_EQ(robot_.history().size(), 1u);
  EXPECT_EQ(robot_.history()[0].group, "right_arm");
  EXPECT_DOUBLE_EQ(robot_.history()[0].end_time, 4.0);
  EXPECT_DOUBLE_EQ(robot_.time(), 4.0);
  JointState state;
  ASSERT_TRUE(robot_.read_joint_state(state).ok());
  EXPECT_EQ(state.names.size(), 7u + 7u + 2u);  // both arms and the head
  // The tool is where forward kinematics says.
  Eigen::Isometry3d T;
  ASSERT_TRUE(robot_.kinematics().forward("right_arm", kTarget, T).ok());
  EXPECT_TRUE(std::isfinite(T.translation().norm()));
}

TEST_F(SimulatedPr2Test, RefusesViolationsWithAReasonAndNoMotion) {
  const std::vector<double> before = robot_.group_positions("right_arm");
  const auto refuse = [&](const JointTrajectory& t, const std::string& reason) {
    const CallResult r = robot_.send_trajectory("right_arm", t);
    EXPECT_EQ(r.status, Status::kError);
    EXPECT_NE(r.message.find(reason), std::string::npos) << r.message;
    EXPECT_EQ(robot_.group_positions("right_arm"), before);
    EXPECT_TRUE(robot_.history().empty());
  };
  std::vector<double> beyond = kTarget;
  beyond[1] = 2.0;  // shoulder lift stops at 1.3963
  refuse(trajectory({kTarget, beyond}, 5.0), "r_shoulder_lift_joint = 2 is outside");
  refuse(trajectory({kTarget}, 0.1), "above its limit");  // far too fast
  JointTrajectory renamed = trajectory({kTarget}, 5.0);
  std::swap(renamed.joint_names[0], renamed.joint_names[1]);
  refuse(renamed, "expects 'r_shoulder_pan_joint'");
  refuse(trajectory({}, 1.0), "no points");
  JointTrajectory backwards = trajectory({kTarget, kTarget}, 5.0);
  backwards.points[1].time_from_start = 1.0;
  refuse(backwards, "must increase");
  EXPECT_EQ(robot_.send_trajectory("tail", trajectory({kTarget}, 5.0)).status, Status::kError);
}

TEST_F(SimulatedPr2Test, ContinuousJointsTakeTheShortWayRound) {
  std::vector<double> q = robot_.group_positions("right_arm");
  q[6] = 2.0 * M_PI - 0.1;  // the wrist roll: 0.1 rad away, the short way
  EXPECT_TRUE(robot_.send_trajectory("right_arm", trajectory({q}, 0.1)).ok());
}

TEST_F(SimulatedPr2Test, GrippersFollowCommandsAndHoldObjects) {
  GripperState s;
  ASSERT_TRUE(robot_.gripper_state("left", s).ok());
  EXPECT_DOUBLE_EQ(s.position, SimulatedPr2::kGripperMaxOpening);
  ASSERT_TRUE(robot_.command_gripper("left", {0.0}).ok());
  ASSERT_TRUE(robot_.gripper_state("left", s).ok());
  EXPECT_TRUE(s.closed);
  EXPECT_FALSE(s.holding_object);
  robot_.object_between_fingers = [](const std::string& g) -> std::optional<double> {
    return g == "right" ? std::optional<double>(0.04) : std::nullopt;
  };
  ASSERT_TRUE(robot_.command_gripper("right", {0.0}).ok());
  ASSERT_TRUE(robot_.gripper_state("right", s).ok());
  EXPECT_TRUE(s.holding_object);
  EXPECT_DOUBLE_EQ(s.position, 0.04);
  ASSERT_TRUE(robot_.command_gripper("right", {0.08}).ok());
  ASSERT_TRUE(robot_.gripper_state("right", s).ok());
  EXPECT_FALSE(s.closed);
  EXPECT_DOUBLE_EQ(s.position, 0.08);
  EXPECT_EQ(robot_.command_gripper("right", {0.5}).status, Status::kError);
  EXPECT_EQ(robot_.command_gripper("middle", {0.0}).status, Status::kError);
}

TEST(SimulatedPr2Lifecycle, AnswersEveryMethodInEveryStateAsTheInterfaceDocuments) {
  SimulatedPr2 robot;
  test::expect_lifecycle_table(robot, *robot.kinematics().group("left_arm"), "left");
}

TEST(Pr2Kinematics, BaseFramePosesDependOnTheTorsoAndSensorPoseIsTheHeadKinect) {
  const Pr2Kinematics low(RobotModel::pr2(), 0.0), high(RobotModel::pr2(), 0.3);
  Eigen::Isometry3d a, b;
  const std::vector<double> q(7, 0.0);
  ASSERT_TRUE(low.forward("left_arm", q, a).ok());
  ASSERT_TRUE(high.forward("left_arm", q, b).ok());
  EXPECT_NEAR(b.translation().z() - a.translation().z(), 0.3, 1e-12);
  // IK in the base frame, at the raised torso, reproduces the pose.
  const IkResult r = high.inverse("left_arm", b, {});
  ASSERT_TRUE(r.success) << r.message;
  Eigen::Isometry3d c;
  ASSERT_TRUE(high.forward("left_arm", r.joints, c).ok());
  EXPECT_LT((c.translation() - b.translation()).norm(), 1e-3);
  EXPECT_THROW(Pr2Kinematics(RobotModel::pr2(), 0.5), Error);  // the torso travels 0.33 m
  SimulatedPr2 robot;
  ASSERT_TRUE(robot.configure().ok());
  Eigen::Isometry3d sensor;
  ASSERT_TRUE(robot.sensor_pose(sensor).ok());
  EXPECT_GT(sensor.translation().z(), 1.0);    // head height
  EXPECT_GT(sensor.linear().col(2).x(), 0.9);  // the optical axis looks forward
}

// The robot factory every front end starts its PR2 from (pr2/pr2_robots.h).
TEST(Pr2Robots, TheSimulatedPr2StartsActiveAtItsTorsoAndARealOnesKinematicsFollowItsState) {
  SimulatedPr2 robot = start_simulated_pr2(0.2);
  EXPECT_EQ(robot.state(), LifecycleState::kActive);
  EXPECT_DOUBLE_EQ(robot.kinematics().torso_height(), 0.2);
  // A real PR2 reports its torso among its joints (lmk pbd run --ros).
  JointState state;
  state.names = {"head_pan_joint", "torso_lift_joint"};
  state.positions = {0.1, 0.25};
  EXPECT_DOUBLE_EQ(pr2_kinematics_at(state).torso_height(), 0.25);
  // A torso out of the joint's limits is refused by the model, and a state without the torso
  // joint is no PR2's.
  EXPECT_THROW(start_simulated_pr2(5.0), Error);
  JointState no_torso;
  no_torso.names = {"head_pan_joint"};
  no_torso.positions = {0.0};
  EXPECT_NE(test::error_of([&] { pr2_kinematics_at(no_torso); }).find("no torso_lift_joint"),
            std::string::npos);
}

}  // namespace
}  // namespace lmk
