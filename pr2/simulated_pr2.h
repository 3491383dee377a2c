// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A simulated PR2 behind RobotInterface, for tests and for running PbD programs without hardware.
//
// - Lifecycle: configure, then activate; motion commands are refused unless active. Configuring
//   puts the arms at the robot's sides (pr2_arms_at_sides()), the head and torso at zero.
// - Trajectories run in simulated time and are checked first, whole: joint names in the group's
//   order, increasing times, positions within limits, velocities within each joint's maximum
//   (including the first step from the current state). A violating trajectory is refused with the
//   reason and nothing moves.
// - Grippers open between 0 and 0.09 m. Closing stops at an object's width when the test hook says
//   an object lies between the fingers; the gripper then reports holding it.
// - Every executed motion is recorded for inspection.
// - With a contact world set (issue #60), every executed trajectory is checked against that world's
//   ground truth and the robot's own body; what touched is kept in contacts(), and nothing stops.

#include <functional>
#include <map>
#include <optional>

#include "lmk/pr2/pr2_kinematics.h"
#include "lmk/pr2/trajectory_contacts.h"

namespace lmk {

struct ExecutedMotion {
  std::string group;
  JointTrajectory trajectory;
  double start_time = 0.0, end_time = 0.0;  ///< simulated seconds
};

/// What an executed motion touched.
struct ExecutedContact {
  std::size_t motion = 0;  ///< its index in SimulatedPr2::history()
  std::string group;
  MotionContact contact;  ///< the first contact along it (at: the share of its time)
};

/// The arms' joints where the simulated PR2 starts: at its sides, elbows bent, hands out of the
/// space in front of it.
const std::map<std::string, double>& pr2_arms_at_sides();

class SimulatedPr2 : public RobotInterface {
 public:
  static constexpr double kGripperMaxOpening = 0.09;  ///< m

  explicit SimulatedPr2(Pr2Kinematics kinematics = Pr2Kinematics());

  CallResult configure() override;
  CallResult activate() override;
  CallResult deactivate() override;
  LifecycleState state() const override { return lifecycle_; }
  CallResult read_joint_state(JointState& out) const override;
  CallResult send_trajectory(const std::string& group, const JointTrajectory& trajectory) override;
  CallResult command_gripper(const std::string& gripper, const GripperCommand& command) override;
  CallResult gripper_state(const std::string& gripper, GripperState& out) const override;
  CallResult sensor_pose(Eigen::Isometry3d& T_base_sensor) const override;

  /// Test hook: the width of the object between the named gripper's fingers, if any.
  std::function<std::optional<double>(const std::string& gripper)> object_between_fingers;

  /// The world the robot's motions are checked against (trajectory_contact; lmk's PR2 body): its
  /// ground truth, asked for at every trajectory, so that a world that changes (an object picked
  /// up or moved) is seen as it is. Unset or returning null: nothing is checked.
  std::function<std::shared_ptr<const CollisionScene>()> contact_world;
  /// The first contact of every executed motion that touched the contact world or the robot.
  const std::vector<ExecutedContact>& contacts() const { return contacts_; }

  const Pr2Kinematics& kinematics() const { return kinematics_; }
  const std::vector<ExecutedMotion>& history() const { return history_; }
  /// The current joint values of a group, in its order.
  std::vector<double> group_positions(const std::string& group) const;
  double time() const { return time_; }
  /// Names of the grippers: "left", "right".
  static std::vector<std::string> grippers();

 private:
  CallResult check_trajectory(const GroupInfo& group, const JointTrajectory& t) const;
  /// The contact check of a trajectory about to run (contact_world).
  void record_contact(const std::string& group, const JointTrajectory& trajectory);

  Pr2Kinematics kinematics_;
  LifecycleState lifecycle_ = LifecycleState::kUnconfigured;
  std::map<std::string, double> positions_;  // every group joint, by name
  std::map<std::string, GripperState> grippers_;
  std::vector<ExecutedMotion> history_;
  std::vector<ExecutedContact> contacts_;
  // The contact check's checker, for the world it was built on (its levers measured once).
  std::shared_ptr<const CollisionScene> checked_world_;
  std::shared_ptr<const RobotMotionChecker> contact_checker_;
  double time_ = 0.0;
};

}  // namespace lmk
