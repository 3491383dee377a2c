// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What an executed trajectory touched (issue #60): the simulated PR2's check of every motion it
// runs against its world's ground truth and its own body. Planning checks against what the camera
// saw, with a padding; this checks against what is there, without one, and tells what a real arm
// would have hit. It never stops a motion.

#include <memory>
#include <optional>
#include <string>

#include "lmk/pbd/collision_scene.h"
#include "lmk/pbd/motion_check.h"
#include "lmk/pr2/pr2_kinematics.h"
#include "lmk/pr2/robot_body.h"
#include "lmk/pr2/robot_motion_checker.h"

namespace lmk {

struct TrajectoryContactSettings {
  /// The trajectory is sampled so that no point of the robot moves more than this between two
  /// samples, m.
  double step = 0.005;
  /// The gripper's links may touch the world within this of the tool frame at the trajectory's
  /// start and end, m: the object it grasps or releases, the surface it places on (as
  /// PlanSettings::intended_contact_radius).
  double intended_radius = 0.08;
};

/// A checker for trajectory_contact: lmk's PR2 `body` against `world`, the robot at `state`; it
/// looks `settings.step` beyond each link, and counts touching (distance below zero) only.
RobotMotionChecker contact_checker(std::shared_ptr<const RobotBody> body,
                                   std::shared_ptr<const CollisionScene> world,
                                   const Pr2Kinematics& kinematics, const JointValues& state,
                                   const TrajectoryContactSettings& settings = {});

/// The first configuration along `trajectory` of `group` where a link it moves goes inside the
/// checker's world ("the world") or another link of the robot ("the robot's <link>"; distance
/// below zero; `at` is the share of the trajectory's time), run from `state` (every joint the
/// robot has; the first point is reached from there; continuous joints turn the shorter way).
/// Nothing when it touched nothing. `checker`: contact_checker's, standing at `state`.
std::optional<MotionContact> trajectory_contact(const RobotMotionChecker& checker,
                                                const Pr2Kinematics& kinematics,
                                                const std::string& group, const JointValues& state,
                                                const JointTrajectory& trajectory,
                                                const TrajectoryContactSettings& settings = {});

/// "link r_forearm_link went 1.2 mm into the world near (0.56, -0.40, 0.82) m in base_link, 52% of
/// the way": a contact trajectory_contact found, as it happened.
std::string describe_touch(const MotionContact& contact);

/// The ground truth of a world for trajectory_contact: points over every triangle of its mesh
/// (base frame), no farther apart than `spacing`, nothing hidden.
std::shared_ptr<const CollisionScene> ground_truth_scene(
    const std::vector<Eigen::Vector3d>& vertices, const std::vector<Eigen::Vector3i>& triangles,
    double spacing = 0.005);

}  // namespace lmk
