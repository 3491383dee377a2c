// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pr2/pr2_kinematics.h"

#include "lmk/geometry/error.h"

namespace lmk {

namespace {
constexpr const char* kBase = "base_link";
constexpr const char* kTorso = "torso_lift_link";
}  // namespace

const std::map<std::string, GroupLinks>& pr2_groups() {
  static const std::map<std::string, GroupLinks> groups = {
      {"left_arm", {kTorso, "l_gripper_tool_frame"}},
      {"right_arm", {kTorso, "r_gripper_tool_frame"}},
      {"head", {kTorso, "head_mount_kinect_rgb_optical_frame"}},
  };
  return groups;
}

Pr2Kinematics::Pr2Kinematics(const RobotModel& model, double torso_height, const IkSettings& ik)
    : torso_height_(torso_height), ik_(ik) {
  const KinematicChain torso = model.chain(kBase, kTorso);
  const JointInfo lift = torso.moving_joints().at(0);
  if (!(torso_height >= lift.lower && torso_height <= lift.upper)) {
    throw Error("torso height " + std::to_string(torso_height) + " m is outside [" +
                std::to_string(lift.lower) + ", " + std::to_string(lift.upper) + "] m");
  }
  T_base_torso_ = torso.forward({torso_height});
  for (const auto& [name, links] : pr2_groups()) {
    if (model.has_link(links.tip)) chains_.emplace(name, model.chain(links.root, links.tip));
  }
  if (chains_.empty())
    throw Error(model.name() + ": none of the PR2 groups' links is in the model");
}

std::vector<std::string> Pr2Kinematics::groups() const {
  std::vector<std::string> names;
  for (const auto& [name, chain] : chains_) names.push_back(name);
  return names;
}

std::optional<GroupInfo> Pr2Kinematics::group(const std::string& name) const {
  const auto it = chains_.find(name);
  if (it == chains_.end()) return std::nullopt;
  return GroupInfo{name, it->second.root_link(), it->second.tip_link(), it->second.moving_joints()};
}

CallResult Pr2Kinematics::forward(const std::string& group, const std::vector<double>& joints,
                                  Eigen::Isometry3d& T_base_tool) const {
  const auto it = chains_.find(group);
  if (it == chains_.end()) return CallResult::error("unknown group '" + group + "'");
  if (joints.size() != it->second.dof()) {
    return CallResult::error("group '" + group + "' has " + std::to_string(it->second.dof()) +
                             " joints, got " + std::to_string(joints.size()) + " values");
  }
  T_base_tool = T_base_torso_ * it->second.forward(joints);
  return CallResult::success();
}

IkResult Pr2Kinematics::inverse(const std::string& group, const Eigen::Isometry3d& T_base_tool,
                                const std::vector<double>& seed) const {
  const auto it = chains_.find(group);
  if (it == chains_.end()) {
    IkResult r;
    r.failure = IkFailure::kBadRequest;
    r.message = "unknown group '" + group + "'";
    return r;
  }
  return solve_ik(it->second, T_base_torso_.inverse() * T_base_tool, seed, ik_);
}

}  // namespace lmk
