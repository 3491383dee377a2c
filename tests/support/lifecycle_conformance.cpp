// SPDX-License-Identifier: BSD-3-Clause
#include "tests/support/lifecycle_conformance.h"

#include <gtest/gtest.h>

#include <map>

namespace lmk::test {
namespace {

/// Holds the group's arm where it is, for one second: a trajectory any robot accepts.
JointTrajectory hold_trajectory(RobotInterface& robot, const GroupInfo& group) {
  JointState state;
  EXPECT_TRUE(robot.read_joint_state(state).ok());
  std::map<std::string, double> now;
  for (std::size_t i = 0; i < state.names.size(); ++i) now[state.names[i]] = state.positions[i];
  JointTrajectory t;
  JointTrajectory::Point point;
  for (const JointInfo& joint : group.joints) {
    const auto it = now.find(joint.name);
    if (it == now.end()) return {};
    t.joint_names.push_back(joint.name);
    point.positions.push_back(it->second);
  }
  point.time_from_start = 1.0;
  t.points.push_back(point);
  return t;
}

void expect_refused(const CallResult& r, const std::string& method, LifecycleState state) {
  EXPECT_EQ(r.status, Status::kError) << method << " in " << lifecycle_state_name(state);
  EXPECT_NE(r.message.find(method), std::string::npos) << r.message;
  EXPECT_NE(r.message.find(lifecycle_state_name(state)), std::string::npos) << r.message;
}

void expect_reads(RobotInterface& robot, const std::string& gripper, bool allowed) {
  const LifecycleState state = robot.state();
  JointState joints;
  GripperState grip;
  Eigen::Isometry3d T_base_sensor;
  const CallResult results[] = {robot.read_joint_state(joints), robot.gripper_state(gripper, grip),
                                robot.sensor_pose(T_base_sensor)};
  const char* methods[] = {"read_joint_state", "gripper_state", "sensor_pose"};
  for (int i = 0; i < 3; ++i) {
    if (allowed) {
      EXPECT_TRUE(results[i].ok()) << methods[i] << ": " << results[i].message;
    } else {
      expect_refused(results[i], methods[i], state);
    }
    EXPECT_EQ(robot.state(), state);
  }
}

void expect_commands_refused(RobotInterface& robot, const GroupInfo& group,
                             const std::string& gripper, const JointTrajectory& hold) {
  const LifecycleState state = robot.state();
  expect_refused(robot.send_trajectory(group.name, hold), "send_trajectory", state);
  GripperCommand open;
  open.position = 0.08;
  expect_refused(robot.command_gripper(gripper, open), "command_gripper", state);
  EXPECT_EQ(robot.state(), state);
}

}  // namespace

void expect_lifecycle_table(RobotInterface& robot, const GroupInfo& group,
                            const std::string& gripper) {
  using S = LifecycleState;
  ASSERT_EQ(robot.state(), S::kUnconfigured);
  expect_refused(robot.activate(), "activate", S::kUnconfigured);
  EXPECT_EQ(robot.state(), S::kUnconfigured);
  EXPECT_TRUE(robot.deactivate().ok());
  EXPECT_EQ(robot.state(), S::kUnconfigured);
  expect_reads(robot, gripper, false);
  expect_commands_refused(robot, group, gripper, JointTrajectory());

  ASSERT_TRUE(robot.configure().ok());
  EXPECT_EQ(robot.state(), S::kInactive);
  EXPECT_TRUE(robot.configure().ok());  // reconfiguring an inactive robot is allowed
  EXPECT_EQ(robot.state(), S::kInactive);
  expect_reads(robot, gripper, true);
  const JointTrajectory hold = hold_trajectory(robot, group);
  ASSERT_FALSE(hold.joint_names.empty()) << "no joint of " << group.name << " in the joint state";
  expect_commands_refused(robot, group, gripper, hold);
  EXPECT_TRUE(robot.deactivate().ok());
  EXPECT_EQ(robot.state(), S::kInactive);

  ASSERT_TRUE(robot.activate().ok());
  EXPECT_EQ(robot.state(), S::kActive);
  EXPECT_TRUE(robot.activate().ok());
  EXPECT_EQ(robot.state(), S::kActive);
  expect_refused(robot.configure(), "configure", S::kActive);
  EXPECT_EQ(robot.state(), S::kActive);
  expect_reads(robot, gripper, true);
  const CallResult moved = robot.send_trajectory(group.name, hold);
  EXPECT_TRUE(moved.ok()) << moved.message;
  GripperCommand open;
  open.position = 0.08;
  const CallResult opened = robot.command_gripper(gripper, open);
  EXPECT_TRUE(opened.ok()) << opened.message;

  EXPECT_TRUE(robot.deactivate().ok());
  EXPECT_EQ(robot.state(), S::kInactive);
  expect_commands_refused(robot, group, gripper, hold);
}

}  // namespace lmk::test
