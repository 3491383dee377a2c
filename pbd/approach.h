// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Approach and retreat along the gripper's axis (issue #60), as PR2 PbD users expect of a grasp: a
// demonstrated grasp pose is reached from a pre-grasp pose `distance` back along the tool frame's
// x axis (the way the fingers point), gripper open, so that the fingers slide onto the object
// instead of sweeping sideways into it; and after a release the hand backs off the same way before
// it goes on. A program that demonstrates its own approach or retreat (the step before a grasp
// already stands on that line) gains none.

#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lmk/pbd/program.h"

namespace lmk {

/// The farthest approach a plan takes (PlanSettings::approach), m: farther back, a pre-grasp is a
/// step of its own to demonstrate.
inline constexpr double kMaxApproach = 0.3;

/// Which motion of a program step a planned step is.
enum class Phase {
  kTarget,    ///< to the step's demonstrated target
  kApproach,  ///< to the pre-grasp pose before a grasp
  kRetreat,   ///< back off along the gripper's axis after a release
};
/// "target", "approach" or "retreat".
const char* phase_name(Phase phase);
/// A planned step for a person: "step 3" (its target), "step 3's approach".
std::string step_name(std::size_t step, Phase phase);

/// One arm's goal in one motion: where its tool frame goes (base frame) and then its gripper.
struct ArmGoal {
  Arm arm = Arm::kRight;
  std::string frame;  ///< the program's frame for the step: kBaseFrame or the landmark
  Eigen::Isometry3d T_base_ee = Eigen::Isometry3d::Identity();
  GripperAction gripper = GripperAction::kOpen;
};

/// One motion of the arms within a program step.
struct StepMotion {
  Phase phase = Phase::kTarget;
  std::vector<ArmGoal> goals;  ///< the arms that move, left first
};

/// The motions program step `s` takes, in order: the approach (for its arms that grasp and need
/// one), its targets, the retreat (for its arms that release and need one). A grasp closes a
/// gripper the arm's previous step left open; a release opens one it left closed; an arm's first
/// step is neither (how its fingers stand before the program is not known). `in_base` gives a
/// step's target in the base frame. `distance` 0: no approach or retreat, one motion per step.
std::vector<StepMotion> step_motions(
    const Program& program, std::size_t s, double distance,
    const std::function<Eigen::Isometry3d(const ArmTarget&)>& in_base);

/// The pre-grasp (and post-release) pose: `T_base_ee` moved `distance` back along its own x axis.
Eigen::Isometry3d backed_off(const Eigen::Isometry3d& T_base_ee, double distance);

/// Whether `other` already lies on the line a hand at `T_base_ee` comes in or backs off along:
/// about the same orientation, and behind it along its x axis by at least half of `distance`
/// within a couple of centimetres of the axis.
bool on_approach_line(const Eigen::Isometry3d& T_base_ee, const Eigen::Isometry3d& other,
                      double distance);

}  // namespace lmk
