// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A path between two joint vectors through free configurations (issue #60): OMPL's RRT-Connect in
// the joints' box, then shortened and smoothed. The search checks its motions at five times the
// step first, and the path it finds at the step; one that fails there is searched for again at the
// step. Its budget is counted in configurations checked
// as well as in seconds, and every random draw comes from the settings' seed: given the same
// inputs and a budget the clock does not cut short, it returns the same path on any machine, at
// any load, under a sanitizer.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "lmk/pbd/robot_interface.h"

namespace lmk {

struct JointSpacePlannerSettings {
  double seconds = 2.0;               ///< wall-clock budget, s (> 0)
  std::size_t checks = 20000;         ///< configurations the search and smoothing may check (> 0)
  std::uint64_t seed = 1;             ///< the search's and the smoothing's random draws
  double smoothing_share = 0.5;       ///< of what the search spent, also given to the smoothing
  std::size_t smoothing_floor = 500;  ///< configurations the smoothing gets however fast the search
};

struct JointSpacePath {
  bool found = false;
  /// Joint vectors after the start, the goal last; within the joints' limits.
  std::vector<std::vector<double>> waypoints;
  std::size_t checks = 0;  ///< configurations checked, the search and the smoothing together
  /// When none was found, why: "no collision-free path within 2 s" (or "within 20000
  /// configurations checked"), or an end that cannot be passed through ("no path: the goal is
  /// outside r_upper_arm_roll_joint's limits", "no path: the start is not free").
  std::string why;
};

/// `free(q)` says whether the joint vector q (ordered as `joints`) may be passed through; a motion
/// between two states is checked at states no farther apart than `max_step` (joint-space norm).
/// A continuous joint may turn up to half a turn beyond either end. Throws lmk::Error for sizes
/// that disagree or a non-positive step or budget.
JointSpacePath plan_joint_path(const std::vector<JointInfo>& joints,
                               const std::vector<double>& start, const std::vector<double>& goal,
                               const std::function<bool(const std::vector<double>&)>& free,
                               double max_step, const JointSpacePlannerSettings& settings);

}  // namespace lmk
