// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The generic robot interface PbD drives. pbd knows no particular robot: the same program runs on a
// simulated PR2 in tests, on the real PR2, or on another arm, behind these two interfaces.
//
// Hardware boundary rules (after ros2_control's hardware_interface):
// - every call returns a Status and a message; nothing throws across the boundary;
// - a lifecycle: configure, then activate; commands are refused unless active (below);
// - poses are tool frames in the robot's base frame, T_base_tool.
//
// The lifecycle, per method. "error" is a CallResult with Status::kError whose message names the
// method and the state ("send_trajectory: the robot is inactive; activate it first"); the state
// does not change on an error, and nothing moves.
//
//   method              unconfigured          inactive                  active
//   configure()         -> inactive           reconfigures; inactive    error (deactivate first)
//   activate()          error                 -> active                 ok, stays active
//   deactivate()        ok, stays             ok, stays                 -> inactive; stops motion
//   read_joint_state()  error                 ok                        ok
//   gripper_state()     error                 ok                        ok
//   sensor_pose()       error                 ok                        ok
//   send_trajectory()   error                 error                     executes
//   command_gripper()   error                 error                     executes
//   state()             any state, never fails
//
// configure() connects to the hardware (a real robot: its controllers and joint states) and may
// fail with the reason, staying unconfigured; a failure while active may move the robot to
// inactive (Status::kDeactivate), and the message says why.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace lmk {

enum class Status {
  kOk,          ///< done
  kError,       ///< refused or failed; the message says why, and nothing moved
  kDeactivate,  ///< the hardware asks to be deactivated (e.g. a fault); the message says why
};

enum class LifecycleState { kUnconfigured, kInactive, kActive };
/// "unconfigured", "inactive" or "active".
const char* lifecycle_state_name(LifecycleState state);

struct CallResult {
  Status status = Status::kOk;
  std::string message;
  bool ok() const { return status == Status::kOk; }
  static CallResult success() { return {}; }
  static CallResult error(std::string why) { return {Status::kError, std::move(why)}; }
};

/// What `method` called in the wrong `state` returns: "send_trajectory: the robot is inactive;
/// activate it first" (configure it first, or deactivate it first, as the state requires).
CallResult lifecycle_error(const std::string& method, LifecycleState state);

struct JointState {
  std::vector<std::string> names;
  std::vector<double> positions;   ///< rad or m
  std::vector<double> velocities;  ///< rad/s or m/s
  double stamp = 0.0;              ///< seconds of robot time
};

/// A joint trajectory for one group: waypoints of that group's joints, in the group's order.
struct JointTrajectory {
  struct Point {
    std::vector<double> positions;
    double time_from_start = 0.0;  ///< seconds after the trajectory starts
  };
  std::vector<std::string> joint_names;
  std::vector<Point> points;
};

struct GripperCommand {
  double position = 0.0;     ///< opening between the fingers, m
  double max_effort = -1.0;  ///< N; negative for the gripper's default
};

struct GripperState {
  double position = 0.0;        ///< current opening, m
  bool closed = false;          ///< closed as far as it goes, or closed on an object
  bool holding_object = false;  ///< stopped by an object before closing fully
};

class RobotInterface {
 public:
  virtual ~RobotInterface() = default;

  virtual CallResult configure() = 0;
  virtual CallResult activate() = 0;
  virtual CallResult deactivate() = 0;
  /// Where the robot is in its lifecycle (the table above).
  virtual LifecycleState state() const = 0;

  virtual CallResult read_joint_state(JointState& out) const = 0;
  /// Executes the trajectory on the named group ("left_arm", "right_arm"), or refuses it with a
  /// reason and no motion.
  virtual CallResult send_trajectory(const std::string& group,
                                     const JointTrajectory& trajectory) = 0;
  virtual CallResult command_gripper(const std::string& gripper, const GripperCommand& command) = 0;
  virtual CallResult gripper_state(const std::string& gripper, GripperState& out) const = 0;
  /// Pose of the depth sensor's optical frame in the base frame, T_base_sensor, so that scenes can
  /// be expressed in the base frame.
  virtual CallResult sensor_pose(Eigen::Isometry3d& T_base_sensor) const = 0;
};

/// A robot that passes every call on to `inner`: derive from it to watch or change a few calls (a
/// simulated person who moves things as the arm goes, a log of what was sent) and forward the rest.
/// `inner` must outlive it.
class ForwardingRobot : public RobotInterface {
 public:
  explicit ForwardingRobot(RobotInterface& inner) : inner_(inner) {}

  CallResult configure() override { return inner_.configure(); }
  CallResult activate() override { return inner_.activate(); }
  CallResult deactivate() override { return inner_.deactivate(); }
  LifecycleState state() const override { return inner_.state(); }
  CallResult read_joint_state(JointState& out) const override {
    return inner_.read_joint_state(out);
  }
  CallResult send_trajectory(const std::string& group, const JointTrajectory& trajectory) override {
    return inner_.send_trajectory(group, trajectory);
  }
  CallResult command_gripper(const std::string& gripper, const GripperCommand& command) override {
    return inner_.command_gripper(gripper, command);
  }
  CallResult gripper_state(const std::string& gripper, GripperState& out) const override {
    return inner_.gripper_state(gripper, out);
  }
  CallResult sensor_pose(Eigen::Isometry3d& T_base_sensor) const override {
    return inner_.sensor_pose(T_base_sensor);
  }

 private:
  RobotInterface& inner_;
};

struct JointInfo {
  std::string name;
  std::string type;                 ///< "revolute", "continuous" or "prismatic"
  double lower = 0.0, upper = 0.0;  ///< position limits; unused for continuous joints
  double max_velocity = 0.0;
  bool continuous() const { return type == "continuous"; }
};

struct GroupInfo {
  std::string name;
  std::string root_link;          ///< e.g. torso_lift_link
  std::string tip_link;           ///< the tool frame, e.g. r_gripper_tool_frame
  std::vector<JointInfo> joints;  ///< the moving joints from root to tip, in order
};

/// Why an IK request failed.
enum class IkFailure { kNone, kOutOfWorkspace, kJointLimits, kNoConvergence, kBadRequest };

struct IkResult {
  bool success = false;
  std::vector<double> joints;   ///< the solution, or the best attempt
  double position_error = 0.0;  ///< m
  double rotation_error = 0.0;  ///< rad
  IkFailure failure = IkFailure::kNone;
  std::string message;  ///< why it failed, for a person
};

class KinematicsInterface {
 public:
  virtual ~KinematicsInterface() = default;
  virtual std::vector<std::string> groups() const = 0;
  virtual std::optional<GroupInfo> group(const std::string& name) const = 0;
  /// T_base_tool of the group for the given joint values (the group's order).
  virtual CallResult forward(const std::string& group, const std::vector<double>& joints,
                             Eigen::Isometry3d& T_base_tool) const = 0;
  virtual IkResult inverse(const std::string& group, const Eigen::Isometry3d& T_base_tool,
                           const std::vector<double>& seed) const = 0;
  virtual bool reachable(const std::string& group, const Eigen::Isometry3d& T_base_tool) const {
    return inverse(group, T_base_tool, {}).success;
  }
};

}  // namespace lmk
