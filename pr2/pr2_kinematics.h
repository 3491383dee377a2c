// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The PR2's kinematics behind the generic KinematicsInterface. Groups follow the PR2 SRDF:
// "left_arm" and "right_arm" (7 joints each, torso_lift_link to *_gripper_tool_frame) and "head"
// (pan and tilt, to the head Kinect's optical frame). Every pose is in base_link, for a given torso
// height.

#include <map>

#include "lmk/pr2/ik_solver.h"
#include "lmk/pr2/robot_model.h"

namespace lmk {

/// Root and tip links of each PR2 group.
struct GroupLinks {
  std::string root, tip;
};
const std::map<std::string, GroupLinks>& pr2_groups();

class Pr2Kinematics : public KinematicsInterface {
 public:
  /// Uses `model` (lmk's own description by default, or any PR2 URDF, such as the full one).
  /// Throws lmk::Error when the model lacks base_link, the torso or every group's links, or the
  /// torso height is outside the torso joint's limits.
  explicit Pr2Kinematics(const RobotModel& model = RobotModel::pr2(), double torso_height = 0.0,
                         const IkSettings& ik = {});

  std::vector<std::string> groups() const override;
  std::optional<GroupInfo> group(const std::string& name) const override;
  CallResult forward(const std::string& group, const std::vector<double>& joints,
                     Eigen::Isometry3d& T_base_tool) const override;
  IkResult inverse(const std::string& group, const Eigen::Isometry3d& T_base_tool,
                   const std::vector<double>& seed) const override;

  double torso_height() const { return torso_height_; }
  /// T_base_link_torso_lift_link at the current torso height.
  const Eigen::Isometry3d& T_base_torso() const { return T_base_torso_; }

 private:
  std::map<std::string, KinematicChain> chains_;  // group -> chain from torso_lift_link
  double torso_height_;
  Eigen::Isometry3d T_base_torso_;
  IkSettings ik_;
};

}  // namespace lmk
