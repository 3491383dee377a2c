// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pr2/simulated_pr2.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "lmk/pr2/pr2_motion_check.h"

namespace lmk {
namespace {

// The joint's travel from a to b: the shorter way round for continuous joints.
double travel(const JointInfo& j, double a, double b) {
  return j.continuous() ? std::abs(std::remainder(b - a, 2.0 * M_PI)) : std::abs(b - a);
}

std::string format(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

const std::map<std::string, double>& pr2_arms_at_sides() {
  static const std::map<std::string, double> pose = {
      {"r_shoulder_pan_joint", -1.2},  {"r_shoulder_lift_joint", 1.0},
      {"r_upper_arm_roll_joint", 0.0}, {"r_elbow_flex_joint", -1.6},
      {"r_forearm_roll_joint", 0.0},   {"r_wrist_flex_joint", -0.6},
      {"r_wrist_roll_joint", 0.0},     {"l_shoulder_pan_joint", 1.2},
      {"l_shoulder_lift_joint", 1.0},  {"l_upper_arm_roll_joint", 0.0},
      {"l_elbow_flex_joint", -1.6},    {"l_forearm_roll_joint", 0.0},
      {"l_wrist_flex_joint", -0.6},    {"l_wrist_roll_joint", 0.0}};
  return pose;
}

SimulatedPr2::SimulatedPr2(Pr2Kinematics kinematics) : kinematics_(std::move(kinematics)) {}

std::vector<std::string> SimulatedPr2::grippers() { return {"left", "right"}; }

CallResult SimulatedPr2::configure() {
  if (lifecycle_ == LifecycleState::kActive) return lifecycle_error("configure", lifecycle_);
  positions_.clear();
  // Every joint starts at zero, or at the nearest limit when zero is outside its range; then the
  // arms go to their sides.
  for (const std::string& name : kinematics_.groups()) {
    const GroupInfo info = *kinematics_.group(name);  // keep the group alive while iterating it
    for (const JointInfo& j : info.joints) {
      positions_[j.name] = j.continuous() ? 0.0 : std::clamp(0.0, j.lower, j.upper);
    }
  }
  // The arms at the robot's sides, elbows bent, hands out of the space in front (issue #60): where
  // a PR2 waits, and nowhere inside the world it is about to act in.
  for (const auto& [name, value] : pr2_arms_at_sides()) {
    if (positions_.count(name)) positions_[name] = value;
  }
  for (const std::string& g : grippers())
    grippers_[g] = GripperState{kGripperMaxOpening, false, false};
  lifecycle_ = LifecycleState::kInactive;
  return CallResult::success();
}

CallResult SimulatedPr2::activate() {
  if (lifecycle_ == LifecycleState::kUnconfigured) return lifecycle_error("activate", lifecycle_);
  lifecycle_ = LifecycleState::kActive;
  return CallResult::success();
}

CallResult SimulatedPr2::deactivate() {
  if (lifecycle_ == LifecycleState::kActive) lifecycle_ = LifecycleState::kInactive;
  return CallResult::success();
}

CallResult SimulatedPr2::read_joint_state(JointState& out) const {
  if (lifecycle_ == LifecycleState::kUnconfigured)
    return lifecycle_error("read_joint_state", lifecycle_);
  out = JointState();
  for (const auto& [name, q] : positions_) {
    out.names.push_back(name);
    out.positions.push_back(q);
    out.velocities.push_back(0.0);  // between trajectories the simulated robot is at rest
  }
  out.stamp = time_;
  return CallResult::success();
}

std::vector<double> SimulatedPr2::group_positions(const std::string& group) const {
  std::vector<double> q;
  if (const auto info = kinematics_.group(group)) {
    for (const JointInfo& j : info->joints) q.push_back(positions_.at(j.name));
  }
  return q;
}

CallResult SimulatedPr2::check_trajectory(const GroupInfo& group, const JointTrajectory& t) const {
  const auto& joints = group.joints;
  if (t.joint_names.size() != joints.size()) {
    return CallResult::error("trajectory for '" + group.name + "' names " +
                             std::to_string(t.joint_names.size()) + " joints; the group has " +
                             std::to_string(joints.size()));
  }
  for (std::size_t i = 0; i < joints.size(); ++i) {
    if (t.joint_names[i] != joints[i].name) {
      return CallResult::error("trajectory joint " + std::to_string(i) + " is '" +
                               t.joint_names[i] + "'; group '" + group.name + "' expects '" +
                               joints[i].name + "'");
    }
  }
  if (t.points.empty()) return CallResult::error("trajectory has no points");
  std::vector<double> previous = group_positions(group.name);
  double previous_time = 0.0;
  for (std::size_t p = 0; p < t.points.size(); ++p) {
    const auto& point = t.points[p];
    const std::string where = "point " + std::to_string(p);
    if (point.positions.size() != joints.size()) {
      return CallResult::error(where + " has " + std::to_string(point.positions.size()) +
                               " positions for " + std::to_string(joints.size()) + " joints");
    }
    if (!(point.time_from_start > previous_time) || !std::isfinite(point.time_from_start)) {
      return CallResult::error(where + ": time_from_start must increase, and start above 0");
    }
    const double dt = point.time_from_start - previous_time;
    for (std::size_t i = 0; i < joints.size(); ++i) {
      const JointInfo& j = joints[i];
      const double q = point.positions[i];
      if (!std::isfinite(q)) return CallResult::error(where + ": " + j.name + " is not finite");
      if (!j.continuous() && (q < j.lower || q > j.upper)) {
        return CallResult::error(where + ": " + j.name + " = " + format(q) + " is outside [" +
                                 format(j.lower) + ", " + format(j.upper) + "]");
      }
      const double velocity = travel(j, previous[i], q) / dt;
      if (velocity > j.max_velocity) {
        return CallResult::error(where + ": " + j.name + " would move at " + format(velocity) +
                                 " per s, above its limit of " + format(j.max_velocity));
      }
    }
    previous = point.positions;
    previous_time = point.time_from_start;
  }
  return CallResult::success();
}

void SimulatedPr2::record_contact(const std::string& group, const JointTrajectory& trajectory) {
  const std::shared_ptr<const CollisionScene> world = contact_world ? contact_world() : nullptr;
  if (!world) return;
  JointValues state = positions_;
  state["torso_lift_joint"] = kinematics_.torso_height();
  if (world != checked_world_) {  // the levers are measured once per world
    contact_checker_ = std::make_shared<const RobotMotionChecker>(
        contact_checker(pr2_body(), world, kinematics_, state));
    checked_world_ = world;
  }
  if (std::optional<MotionContact> c = trajectory_contact(contact_checker_->with_state(state),
                                                          kinematics_, group, state, trajectory))
    contacts_.push_back({history_.size(), group, *c});
}

CallResult SimulatedPr2::send_trajectory(const std::string& group,
                                         const JointTrajectory& trajectory) {
  if (lifecycle_ != LifecycleState::kActive) return lifecycle_error("send_trajectory", lifecycle_);
  const auto info = kinematics_.group(group);
  if (!info) return CallResult::error("unknown group '" + group + "'");
  const CallResult check = check_trajectory(*info, trajectory);
  if (!check.ok()) return check;  // refused whole: nothing moved
  record_contact(group, trajectory);
  const std::vector<double>& final_q = trajectory.points.back().positions;
  for (std::size_t i = 0; i < info->joints.size(); ++i) {
    const JointInfo& j = info->joints[i];
    positions_[j.name] = j.continuous() ? std::remainder(final_q[i], 2.0 * M_PI) : final_q[i];
  }
  const double duration = trajectory.points.back().time_from_start;
  history_.push_back({group, trajectory, time_, time_ + duration});
  time_ += duration;
  return CallResult::success();
}

CallResult SimulatedPr2::command_gripper(const std::string& gripper,
                                         const GripperCommand& command) {
  if (lifecycle_ != LifecycleState::kActive) return lifecycle_error("command_gripper", lifecycle_);
  const auto it = grippers_.find(gripper);
  if (it == grippers_.end())
    return CallResult::error("unknown gripper '" + gripper + "' (left, right)");
  if (!std::isfinite(command.position) || command.position < 0.0 ||
      command.position > kGripperMaxOpening) {
    return CallResult::error("gripper position " + format(command.position) + " m is outside [0, " +
                             format(kGripperMaxOpening) + "]");
  }
  GripperState& s = it->second;
  const std::optional<double> object =
      object_between_fingers ? object_between_fingers(gripper) : std::nullopt;
  if (object && command.position < *object) {
    s = {*object, true, true};  // the fingers stop on the object
  } else {
    s = {command.position, command.position <= 1e-3, false};
  }
  time_ += 1.0;  // a gripper motion takes about a second on the PR2
  return CallResult::success();
}

CallResult SimulatedPr2::gripper_state(const std::string& gripper, GripperState& out) const {
  if (lifecycle_ == LifecycleState::kUnconfigured)
    return lifecycle_error("gripper_state", lifecycle_);
  const auto it = grippers_.find(gripper);
  if (it == grippers_.end())
    return CallResult::error("unknown gripper '" + gripper + "' (left, right)");
  out = it->second;
  return CallResult::success();
}

CallResult SimulatedPr2::sensor_pose(Eigen::Isometry3d& T_base_sensor) const {
  if (lifecycle_ == LifecycleState::kUnconfigured)
    return lifecycle_error("sensor_pose", lifecycle_);
  return kinematics_.forward("head", group_positions("head"), T_base_sensor);
}

}  // namespace lmk
