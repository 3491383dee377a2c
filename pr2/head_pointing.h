// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Pointing the PR2's head: the pan and tilt that put a target on the head Kinect's optical axis,
// so that the scene the robot sees holds what a program needs.

#include <Eigen/Core>
#include <vector>

#include "lmk/pbd/robot_interface.h"
#include "lmk/pr2/pr2_kinematics.h"

namespace lmk {

/// Head joint values (pan, tilt, within their limits) that point the head Kinect's optical axis
/// at `target` (base frame) as nearly as the limits allow.
std::vector<double> head_joints_looking_at(const Pr2Kinematics& kinematics,
                                           const Eigen::Vector3d& target);

/// Moves the head of `robot` (whose kinematics are `kinematics`) to look at `target`, at a speed
/// within the joints' limits.
CallResult point_head(RobotInterface& robot, const Pr2Kinematics& kinematics,
                      const Eigen::Vector3d& target);

}  // namespace lmk
