// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// RosRobot: RobotInterface over ROS 1, for the real PR2 (docs/ros.md, "Running on a real PR2").
//
// - Joint state from /joint_states (messages that name some joints each are merged).
// - Arms through actionlib: the PR2's pr2_controllers_msgs/JointTrajectoryAction on
//   {l,r}_arm_controller/joint_trajectory_action, or control_msgs/FollowJointTrajectory for any
//   other robot (RosRobotSettings::arm_action_type).
// - Grippers through pr2_controllers_msgs/Pr2GripperCommandAction on
//   {l,r}_gripper_controller/gripper_action; the head through PointHeadAction on
//   head_traj_controller/point_head_action.
// - The sensor pose from TF: the head Kinect's optical frame in the base frame.
//
// Every failure comes back as a CallResult, never as an exception: a goal the controller rejects
// or aborts, or one that does not finish within its trajectory's duration plus a margin (it is
// then cancelled), is an error naming the action and the controller's reason. The lifecycle is
// RobotInterface's (pbd/robot_interface.h): configure() connects to the action servers and waits
// for the first joint state, and fails, naming what is missing, when they do not answer in time.
//
// The node must be spinning (a ros::AsyncSpinner) while RosRobot waits for results and messages.

#include <ros/ros.h>

#include <map>
#include <memory>
#include <string>

#include "lmk/pbd/robot_interface.h"

namespace lmk::ros1 {

struct RosRobotSettings {
  /// "pr2" (pr2_controllers_msgs/JointTrajectoryAction) or "follow_joint_trajectory"
  /// (control_msgs/FollowJointTrajectory).
  std::string arm_action_type = "pr2";
  /// Group -> action namespace. Empty: the PR2's, {l,r}_arm_controller/joint_trajectory_action,
  /// or {l,r}_arm_controller/follow_joint_trajectory for follow_joint_trajectory.
  std::map<std::string, std::string> arm_actions;
  /// Gripper ("left", "right") -> action namespace.
  std::map<std::string, std::string> gripper_actions = {
      {"left", "l_gripper_controller/gripper_action"},
      {"right", "r_gripper_controller/gripper_action"}};
  std::string head_action = "head_traj_controller/point_head_action";
  std::string joint_states_topic = "joint_states";
  std::string base_frame = "base_link";
  std::string sensor_frame = "head_mount_kinect_rgb_optical_frame";
  double connect_timeout = 5.0;   ///< s: action servers and the first joint state, at configure()
  double result_margin = 5.0;     ///< s beyond a trajectory's duration before it counts as lost
  double gripper_timeout = 10.0;  ///< s for a gripper goal
  double gripper_max_effort = 50.0;  ///< N when a command asks for the default (negative)

  /// The arm action namespaces arm_action_type implies when arm_actions is empty.
  std::map<std::string, std::string> resolved_arm_actions() const;
  /// From private parameters of the same names (~arm_action_type, ~base_frame, ...); arm and
  /// gripper namespaces as ~left_arm_action, ~right_arm_action, ~left_gripper_action,
  /// ~right_gripper_action. Throws lmk::Error for an unknown arm_action_type or a bad number.
  static RosRobotSettings from_parameters(const ::ros::NodeHandle& private_nh);
};

class RosRobot : public RobotInterface {
 public:
  explicit RosRobot(::ros::NodeHandle nh, RosRobotSettings settings = {});
  ~RosRobot() override;
  RosRobot(const RosRobot&) = delete;
  RosRobot& operator=(const RosRobot&) = delete;

  CallResult configure() override;
  CallResult activate() override;
  CallResult deactivate() override;
  LifecycleState state() const override;
  CallResult read_joint_state(JointState& out) const override;
  CallResult send_trajectory(const std::string& group, const JointTrajectory& trajectory) override;
  CallResult command_gripper(const std::string& gripper, const GripperCommand& command) override;
  CallResult gripper_state(const std::string& gripper, GripperState& out) const override;
  CallResult sensor_pose(Eigen::Isometry3d& T_base_sensor) const override;

  /// Points the head's sensor at `target` (in the base frame) and waits up to `timeout` seconds;
  /// active only, like every command.
  CallResult point_head(const Eigen::Vector3d& target, double timeout = 5.0);

  const RosRobotSettings& settings() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lmk::ros1
