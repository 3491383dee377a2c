// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/ros/ros_eyes.h"

#include <cstdio>

namespace lmk::ros1 {

RosEyes::RosEyes(RosRobot& robot, const LatestFrame& camera, double frame_timeout)
    : robot_(robot), camera_(camera), frame_timeout_(frame_timeout) {}

CallResult RosEyes::look_at(const Eigen::Vector3d& target, PointCloud& frame) {
  const CallResult pointed = robot_.point_head(target);
  if (!pointed.ok()) return pointed;
  // A frame taken while the head still moved would be placed by TF at its own stamp, but smeared
  // by the motion: only one stamped after the action reported the head there is a new look.
  const ::ros::Time settled = ::ros::Time::now();
  const std::shared_ptr<const Frame> seen = camera_.wait_newer(settled, frame_timeout_);
  if (!seen) {
    char why[64];
    std::snprintf(why, sizeof why, " since the head settled, within %.1f s", frame_timeout_);
    return CallResult::error("no frame from " + camera_.topic() + why);
  }
  frame = seen->scene;
  return CallResult::success();
}

}  // namespace lmk::ros1
