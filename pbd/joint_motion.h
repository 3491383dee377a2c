// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Joint-space motions for a group: straight lines between two joint vectors, timed so that no
// joint exceeds a fraction of its speed limit. Continuous joints go the shorter way round.

#include <vector>

#include "lmk/geometry/random.h"
#include "lmk/pbd/robot_interface.h"

namespace lmk {

/// The joint's travel from a to b: the shorter way round for a continuous joint.
double signed_travel(const JointInfo& joint, double a, double b);

/// A value drawn uniformly within the joint's limits (within [-pi, pi] for a continuous joint).
double random_joint(const JointInfo& joint, SplitMix64& rng);
/// random_joint() of each of the group's joints, in its order.
std::vector<double> random_joints(const GroupInfo& group, SplitMix64& rng);

/// The seconds a straight joint-space move from `from` to `to` takes with every joint at most at
/// `speed_fraction` of its limit (0 when nothing moves).
double motion_duration(const GroupInfo& group, const std::vector<double>& from,
                       const std::vector<double>& to, double speed_fraction);

/// The straight line from `from` (the robot's current joints, not a point of the trajectory) to
/// `to`: `points` waypoints evenly spread over `duration` seconds.
JointTrajectory joint_line(const GroupInfo& group, const std::vector<double>& from,
                           const std::vector<double>& to, double duration, int points);

/// The path from `from` through `waypoints` (each a joint vector of the group, the goal last), as
/// straight lines between them over `duration` seconds in all: each line's share of the time in
/// proportion to how long it takes at full speed, and at least `points` waypoints in all (issue
/// #60: a path planned around an obstacle).
JointTrajectory joint_path(const GroupInfo& group, const std::vector<double>& from,
                           const std::vector<std::vector<double>>& waypoints, double duration,
                           int points);

/// The seconds joint_path's path takes with every joint at most at `speed_fraction` of its limit.
double path_duration(const GroupInfo& group, const std::vector<double>& from,
                     const std::vector<std::vector<double>>& waypoints, double speed_fraction);

}  // namespace lmk
