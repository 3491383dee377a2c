// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The pieces of execute() (execute.h) that a watching execution (watch.h) runs step by step,
// checking the landmarks between them. Internal to pbd.

#include "lmk/pbd/execute.h"

namespace lmk {

/// Whether `plan` may run on `robot`: not refused, and the robot where the plan starts. Sets the
/// report's steps_total, started, and error when not.
bool may_start(const Plan& plan, const RobotInterface& robot, const ExecuteSettings& settings,
               ExecutionReport& report);
/// Sends the step's arm trajectories, logging each; false (and the report's error) at the first
/// the robot refuses.
bool send_motions(const PlannedStep& step, RobotInterface& robot, ExecutionReport& report);
/// Commands the step's grippers, logging each; false (and the error) at the first refused.
bool send_gripper_commands(const PlannedStep& step, RobotInterface& robot,
                           const ExecuteSettings& settings, ExecutionReport& report);

}  // namespace lmk
