// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The PR2's head under ROS as the eyes a program looks again with (pbd/look_again.h, issue #46):
// the head is pointed through RosRobot's point-head action, and the look is the camera's first
// frame stamped after the head settled, in the base frame with its sensor placed by TF.

#include "lmk/pbd/look_again.h"
#include "lmk/ros/latest_frame.h"
#include "lmk/ros/ros_robot.h"

namespace lmk::ros1 {

class RosEyes : public Eyes {
 public:
  /// `robot` must be active while looking (point_head is a command); `frame_timeout` s bounds the
  /// wait for a frame after the head settled.
  RosEyes(RosRobot& robot, const LatestFrame& camera, double frame_timeout);
  CallResult look_at(const Eigen::Vector3d& target, PointCloud& frame) override;

 private:
  RosRobot& robot_;
  const LatestFrame& camera_;
  double frame_timeout_;
};

}  // namespace lmk::ros1
