// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Checks a RobotInterface against the lifecycle table in pbd/robot_interface.h, cell by cell, so
// that every robot (the simulated PR2, the ROS one) answers each method in each state alike.

#include <string>

#include "lmk/pbd/robot_interface.h"

namespace lmk::test {

/// Walks a fresh, unconfigured `robot` through unconfigured, inactive and active and back, calling
/// every method in every state, and EXPECTs the table's answer: the state after each call, and for
/// each refusal an error naming the method and the state. In the active state it sends `group` a
/// one-point trajectory (its joints, in order) that holds the arm where it is, and commands
/// `gripper` to open.
void expect_lifecycle_table(RobotInterface& robot, const GroupInfo& group,
                            const std::string& gripper);

}  // namespace lmk::test
