// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A demo scenario whose landmark is moved between two steps (issue #48): the program executed on
// the simulated PR2 while a person moves an object, watching the landmarks through the head
// Kinect (pbd/watch.h) or, as before watching existed, open loop. Internal to the demos.

#include <map>
#include <string>
#include <vector>

#include "lmk/demos/detail/demo_task_definitions.h"
#include "lmk/pbd/execute.h"
#include "lmk/pbd/plan.h"
#include "lmk/pr2/simulated_pr2.h"

namespace lmk::detail {

struct MovedRun {
  ExecutionReport report;
  Plan executed;                     ///< the plan the arm last followed: the first, or a re-plan
  std::vector<std::string> noticed;  ///< what watching noticed (watch.h)
  std::size_t replans = 0;
  std::size_t sent_after_move = 0;  ///< trajectories the arm was sent once the object had moved
};

/// Runs `plan` of `program` on `robot` while `move` happens in `world`; watched through the head
/// Kinect (a frame per look, noise from `seed` on) when `watch`, open loop otherwise.
MovedRun execute_while_moved(const Program& program, const Plan& plan, SimulatedPr2& robot,
                             DemoWorld& world, const DemoMove& move,
                             const std::map<std::string, Landmark>& landmarks, bool watch,
                             const PlanSettings& planning, std::uint64_t seed);

}  // namespace lmk::detail
