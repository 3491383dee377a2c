// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pbd/approach.h"

#include <cmath>

namespace lmk {

namespace {

// How far a demonstrated pose may stray from the approach line and still be the approach: a
// demonstrator guiding the arm by hand is good to a couple of centimetres and some degrees.
constexpr double kOffAxis = 0.02;              // m
constexpr double kTurn = 15.0 * M_PI / 180.0;  // rad
constexpr double kShareOfDistance = 0.5;       // of the approach distance, at least

// The arm's target at the nearest program step before (`step` -1) or after (+1) `s` that moves it.
const ArmTarget* neighbour(const Program& program, std::size_t s, Arm arm, int step) {
  for (long k = static_cast<long>(s) + step; k >= 0 && k < static_cast<long>(program.steps.size());
       k += step) {
    if (const std::optional<ArmTarget>& t = program.steps[static_cast<std::size_t>(k)].arm(arm))
      return &*t;
  }
  return nullptr;
}

}  // namespace

const char* phase_name(Phase phase) {
  switch (phase) {
    case Phase::kApproach:
      return "approach";
    case Phase::kRetreat:
      return "retreat";
    case Phase::kTarget:
      break;
  }
  return "target";
}

std::string step_name(std::size_t step, Phase phase) {
  return "step " + std::to_string(step) +
         (phase == Phase::kTarget ? std::string() : std::string("'s ") + phase_name(phase));
}

Eigen::Isometry3d backed_off(const Eigen::Isometry3d& T_base_ee, double distance) {
  return T_base_ee * Eigen::Translation3d(-distance, 0.0, 0.0);
}

bool on_approach_line(const Eigen::Isometry3d& T_base_ee, const Eigen::Isometry3d& other,
                      double distance) {
  const Eigen::AngleAxisd turn(T_base_ee.linear().transpose() * other.linear());
  if (std::abs(turn.angle()) > kTurn) return false;
  const Eigen::Vector3d v = T_base_ee.inverse() * other.translation();
  return -v.x() >= kShareOfDistance * distance && v.tail<2>().norm() <= kOffAxis;
}

std::vector<StepMotion> step_motions(
    const Program& program, std::size_t s, double distance,
    const std::function<Eigen::Isometry3d(const ArmTarget&)>& in_base) {
  StepMotion approach{Phase::kApproach, {}}, target{Phase::kTarget, {}},
      retreat{Phase::kRetreat, {}};
  for (const Arm arm : {Arm::kLeft, Arm::kRight}) {
    const std::optional<ArmTarget>& t = program.steps[s].arm(arm);
    if (!t) continue;
    const ArmGoal goal{arm, t->frame, in_base(*t), t->gripper};
    target.goals.push_back(goal);
    const ArmTarget* before = neighbour(program, s, arm, -1);
    if (distance <= 0.0 || !before || before->gripper == t->gripper) continue;
    if (t->gripper == GripperAction::kClose) {
      // A grasp: from the pre-grasp pose, fingers open, unless the step before is that pose.
      if (!on_approach_line(goal.T_base_ee, in_base(*before), distance))
        approach.goals.push_back(
            {arm, t->frame, backed_off(goal.T_base_ee, distance), GripperAction::kOpen});
    } else {
      // A release: back off the object before going on, unless the next step does.
      const ArmTarget* after = neighbour(program, s, arm, +1);
      if (!after || !on_approach_line(goal.T_base_ee, in_base(*after), distance))
        retreat.goals.push_back(
            {arm, t->frame, backed_off(goal.T_base_ee, distance), GripperAction::kOpen});
    }
  }
  std::vector<StepMotion> motions;
  for (StepMotion* m : {&approach, &target, &retreat})
    if (!m->goals.empty()) motions.push_back(std::move(*m));
  return motions;
}

}  // namespace lmk
