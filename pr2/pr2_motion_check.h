// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The PR2's motion check for plans (issue #60): PlanSettings::motion_checker built from lmk's PR2
// collision model, the frame the plan searched and the robot's joints at the start. The frame's
// points on the robot's own links (the head camera sees its arms) are left out first.

#include <functional>
#include <memory>

#include "lmk/pbd/plan.h"
#include "lmk/pr2/pr2_kinematics.h"
#include "lmk/pr2/robot_motion_checker.h"

namespace lmk {

struct Pr2MotionCheckSettings {
  MotionCheckSettings motion;
  CollisionSceneSettings scene;
  /// Scene points within this of the robot's links at the start are the robot itself, m; and the
  /// space within this of them is free, not hidden, whatever stood in front of it.
  double self_filter_margin = 0.03;
};

/// lmk's PR2 body (its description's collision shapes), built once per process.
std::shared_ptr<const RobotBody> pr2_body();

/// A PlanSettings::motion_checker for the PR2 `kinematics` describes (its torso height where the
/// start state does not name the torso joint), with `body` (default: pr2_body()).
std::function<std::shared_ptr<const MotionChecker>(const std::vector<const PointCloud*>&,
                                                   const JointState&)>
pr2_motion_checker(const Pr2Kinematics& kinematics, const Pr2MotionCheckSettings& settings = {},
                   std::shared_ptr<const RobotBody> body = nullptr);

}  // namespace lmk
