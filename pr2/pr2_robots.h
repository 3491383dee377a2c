// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Where lmk's front ends get a PR2: `lmk pbd plan/run` (--sim and --ros), lmk serve's plans, the
// Python module and the demo tasks all start their robot here, with the shipped model, instead
// of wiring the model, the kinematics and the lifecycle by hand.

#include "lmk/pbd/robot_interface.h"
#include "lmk/pr2/pr2_kinematics.h"
#include "lmk/pr2/simulated_pr2.h"

namespace lmk {

/// A simulated PR2 with lmk's model, its torso at `torso_height` (m), configured and active: ready
/// to be read, planned for and driven. Throws lmk::Error naming the step that failed.
SimulatedPr2 start_simulated_pr2(double torso_height);

/// The kinematics of a real PR2 as it stands: lmk's model with the torso at the height the robot's
/// joint state reports (torso_lift_joint). Throws lmk::Error when the state has no torso joint.
Pr2Kinematics pr2_kinematics_at(const JointState& state);

}  // namespace lmk
