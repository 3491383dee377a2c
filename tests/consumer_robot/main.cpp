// SPDX-License-Identifier: BSD-3-Clause
// Uses lmk's robot libraries as a PR2 deployment would: the built-in PR2 model and its right arm's
// forward kinematics at the zero pose.
#include <lmk/pr2/robot_model.h>

#include <cstdio>
#include <vector>

int main() {
  const lmk::RobotModel pr2 = lmk::RobotModel::pr2();
  const lmk::KinematicChain arm = pr2.chain("torso_lift_link", "r_wrist_roll_link");
  const Eigen::Vector3d wrist = arm.forward(std::vector<double>(arm.dof(), 0.0)).translation();
  std::printf("%s: right arm of %zu joints, wrist at (%.3f, %.3f, %.3f) m\n", pr2.name().c_str(),
              arm.dof(), wrist.x(), wrist.y(), wrist.z());
  return arm.dof() == 7 && wrist.x() > 0.3 ? 0 : 1;
}
