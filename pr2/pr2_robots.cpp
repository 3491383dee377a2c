// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pr2/pr2_robots.h"

#include "lmk/geometry/error.h"

namespace lmk {

SimulatedPr2 start_simulated_pr2(double torso_height) {
  SimulatedPr2 robot(Pr2Kinematics(RobotModel::pr2(), torso_height));
  const CallResult configured = robot.configure();
  if (!configured.ok()) throw Error("the simulated PR2 failed to configure: " + configured.message);
  const CallResult activated = robot.activate();
  if (!activated.ok()) throw Error("the simulated PR2 failed to activate: " + activated.message);
  return robot;
}

Pr2Kinematics pr2_kinematics_at(const JointState& state) {
  for (std::size_t i = 0; i < state.names.size(); ++i) {
    if (state.names[i] == "torso_lift_joint") {
      return Pr2Kinematics(RobotModel::pr2(), state.positions.at(i));
    }
  }
  throw Error("the robot's joint state has no torso_lift_joint (is it a PR2?)");
}

}  // namespace lmk
