// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Executing a plan through RobotInterface (any robot: the simulated PR2, the real one). Only a
// valid plan moves anything, and only from the joints it was planned from; execution stops at the
// first call the robot refuses and says how far it got.

#include <functional>
#include <string>
#include <vector>

#include "lmk/pbd/plan.h"

namespace lmk {

struct ExecutionReport {
  bool started = false;             ///< false: refused before any command, nothing moved
  bool completed = false;           ///< every step executed
  std::size_t steps_completed = 0;  ///< steps whose motions and gripper commands all succeeded
  std::size_t steps_total = 0;
  std::string error;             ///< why it refused or stopped, for a person
  std::vector<std::string> log;  ///< one line per command sent, in order
};

struct ExecuteSettings {
  /// The robot's arm joints must be within this of the plan's start (rad or m): a robot that moved
  /// since planning would run the first motion from somewhere else.
  double start_tolerance = 1e-3;
  double gripper_open = 0.08;   ///< m, the opening commanded for "open"
  double gripper_closed = 0.0;  ///< m, for "close" (the fingers stop on an object)
  /// Called after each step with (steps done, steps in all).
  std::function<void(std::size_t, std::size_t)> progress;
};

/// Runs `plan` on `robot`, which must be active. Refuses with nothing sent when the plan carries a
/// refusal or the robot is not where the plan starts. Each step sends both arms' trajectories and
/// then commands their grippers; the first call the robot refuses ends the run.
ExecutionReport execute(const Plan& plan, RobotInterface& robot,
                        const ExecuteSettings& settings = {});

}  // namespace lmk
