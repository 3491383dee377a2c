// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A fake PR2 for lmk's ROS tests: the action servers of the arms, grippers and head (the real
// robot's names and message types), /joint_states, TF from lmk's PR2 URDF, and a head Kinect that
// publishes a rendered scene. It records every goal, so that a test can check what the robot was
// asked to do, and can be told to abort an arm goal.

#include <ros/ros.h>
#include <trajectory_msgs/JointTrajectory.h>

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "lmk/geometry/point_cloud.h"

namespace lmk::test {

struct FakePr2Settings {
  double torso_height = 0.0;  ///< m, reported as torso_lift_joint
  /// What the head Kinect sees: a cloud in base_link with T_cloud_sensor = T_base_sensor (how
  /// lmk's renderers and `lmk pbd demo-tasks --save` write scenes). It is published in the
  /// optical frame, and TF places that frame at T_base_sensor.
  PointCloud scene;
  /// What the head Kinect sees after the first, second, ... point-head goal (the last one stays):
  /// a head that turned towards what the first view cut. Their sensor pose is `scene`'s; empty:
  /// `scene` whatever the head does.
  std::vector<PointCloud> scenes_after_head_goals;
  /// What it sees after the first, second, ... arm goal (the last one stays): a landmark a person
  /// moved while the arm was on its way (issue #48). Empty: no such change.
  std::vector<PointCloud> scenes_after_arm_goals;
  std::string cloud_topic = "/head_mount_kinect/depth_registered/points";
  std::string sensor_frame = "head_mount_kinect_rgb_optical_frame";
  double cloud_rate = 4.0;  ///< Hz
};

class FakePr2 {
 public:
  explicit FakePr2(FakePr2Settings settings);
  ~FakePr2();

  /// Goals received by the action server `ns` (e.g. "r_arm_controller/joint_trajectory_action").
  int goals(const std::string& ns) const;
  int total_goals() const;
  /// The trajectories the arm server `ns` received, in order.
  std::vector<trajectory_msgs::JointTrajectory> trajectories(const std::string& ns) const;
  /// The n-th arm goal (1-based, both arms counted together) is aborted instead of executed.
  void abort_arm_goal(int n);
  /// The n-th arm goal never finishes: the server holds it until the client cancels it.
  void hang_arm_goal(int n);
  /// Arm goals the clients cancelled.
  int cancelled_goals() const;
  /// The joint positions now, by name.
  std::map<std::string, double> joints() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lmk::test
