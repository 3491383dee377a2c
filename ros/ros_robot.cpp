// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/ros/ros_robot.h"

#include <actionlib/client/simple_action_client.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <pr2_controllers_msgs/JointTrajectoryAction.h>
#include <pr2_controllers_msgs/PointHeadAction.h>
#include <pr2_controllers_msgs/Pr2GripperCommandAction.h>
#include <ros/callback_queue.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <cstdio>
#include <mutex>

#include "lmk/geometry/error.h"
#include "lmk/ros/tf_lookup.h"

namespace lmk::ros1 {
namespace {

using actionlib::SimpleClientGoalState;

std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", s);
  return text;
}

/// Waits for the goal's end and turns it into a CallResult: succeeded is ok; rejected, aborted,
/// preempted or lost are errors with the controller's text; no result in time cancels the goal.
/// `stalled_is_success` lets a gripper that stopped on an object count as done.
template <class Client>
CallResult wait_for(Client& client, const std::string& what, double timeout,
                    bool stalled_is_success = false) {
  if (!client.waitForResult(::ros::Duration(timeout))) {
    client.cancelGoal();
    return CallResult::error(what + ": no result within " + seconds(timeout) +
                             "; the goal was cancelled");
  }
  const SimpleClientGoalState state = client.getState();
  if (state == SimpleClientGoalState::SUCCEEDED || stalled_is_success) return CallResult::success();
  std::string verb = state.toString();
  for (char& c : verb) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::string text = state.getText();
  return CallResult::error(what + ": the controller " + verb + " the goal" +
                           (text.empty() ? "" : " (" + text + ")"));
}

trajectory_msgs::JointTrajectory to_ros(const JointTrajectory& t) {
  trajectory_msgs::JointTrajectory out;
  out.header.stamp = ::ros::Time(0);  // 0: the controller starts it on arrival
  out.joint_names = t.joint_names;
  for (const JointTrajectory::Point& p : t.points) {
    trajectory_msgs::JointTrajectoryPoint point;
    point.positions = p.positions;
    point.time_from_start = ::ros::Duration(p.time_from_start);
    out.points.push_back(point);
  }
  return out;
}

/// One arm's trajectory action, whichever message type the robot uses.
class ArmClient {
 public:
  virtual ~ArmClient() = default;
  virtual bool connect(double timeout) = 0;
  virtual CallResult execute(const JointTrajectory& t, const std::string& what, double timeout) = 0;
  virtual void cancel() = 0;
};

class Pr2ArmClient : public ArmClient {
 public:
  Pr2ArmClient(::ros::NodeHandle& nh, const std::string& ns) : client_(nh, ns, false) {}
  bool connect(double timeout) override { return client_.waitForServer(::ros::Duration(timeout)); }
  CallResult execute(const JointTrajectory& t, const std::string& what, double timeout) override {
    pr2_controllers_msgs::JointTrajectoryGoal goal;
    goal.trajectory = to_ros(t);
    client_.sendGoal(goal);
    return wait_for(client_, what, timeout);
  }
  void cancel() override { client_.cancelAllGoals(); }

 private:
  actionlib::SimpleActionClient<pr2_controllers_msgs::JointTrajectoryAction> client_;
};

class FollowJointTrajectoryClient : public ArmClient {
 public:
  FollowJointTrajectoryClient(::ros::NodeHandle& nh, const std::string& ns)
      : client_(nh, ns, false) {}
  bool connect(double timeout) override { return client_.waitForServer(::ros::Duration(timeout)); }
  CallResult execute(const JointTrajectory& t, const std::string& what, double timeout) override {
    control_msgs::FollowJointTrajectoryGoal goal;
    goal.trajectory = to_ros(t);
    client_.sendGoal(goal);
    CallResult r = wait_for(client_, what, timeout);
    // A ros_control controller may succeed the action yet report an error code.
    const auto result = client_.getResult();
    if (r.ok() && result &&
        result->error_code != control_msgs::FollowJointTrajectoryResult::SUCCESSFUL) {
      r = CallResult::error(what + ": the controller reports error " +
                            std::to_string(result->error_code) + " (" + result->error_string + ")");
    }
    return r;
  }
  void cancel() override { client_.cancelAllGoals(); }

 private:
  actionlib::SimpleActionClient<control_msgs::FollowJointTrajectoryAction> client_;
};

using GripperClient = actionlib::SimpleActionClient<pr2_controllers_msgs::Pr2GripperCommandAction>;
using HeadClient = actionlib::SimpleActionClient<pr2_controllers_msgs::PointHeadAction>;

}  // namespace

std::map<std::string, std::string> RosRobotSettings::resolved_arm_actions() const {
  if (!arm_actions.empty()) return arm_actions;
  const std::string action =
      arm_action_type == "pr2" ? "joint_trajectory_action" : "follow_joint_trajectory";
  return {{"left_arm", "l_arm_controller/" + action}, {"right_arm", "r_arm_controller/" + action}};
}

RosRobotSettings RosRobotSettings::from_parameters(const ::ros::NodeHandle& private_nh) {
  RosRobotSettings s;
  private_nh.param("arm_action_type", s.arm_action_type, s.arm_action_type);
  if (s.arm_action_type != "pr2" && s.arm_action_type != "follow_joint_trajectory") {
    throw Error("~arm_action_type: '" + s.arm_action_type +
                "' is neither pr2 nor follow_joint_trajectory");
  }
  const auto defaults = s.resolved_arm_actions();
  for (const char* group : {"left_arm", "right_arm"}) {
    std::string ns;
    private_nh.param(std::string(group) + "_action", ns, defaults.at(group));
    s.arm_actions[group] = ns;
  }
  for (const char* gripper : {"left", "right"}) {
    private_nh.param(std::string(gripper) + "_gripper_action", s.gripper_actions[gripper],
                     s.gripper_actions[gripper]);
  }
  private_nh.param("head_action", s.head_action, s.head_action);
  private_nh.param("joint_states_topic", s.joint_states_topic, s.joint_states_topic);
  private_nh.param("base_frame", s.base_frame, s.base_frame);
  private_nh.param("sensor_frame", s.sensor_frame, s.sensor_frame);
  private_nh.param("connect_timeout", s.connect_timeout, s.connect_timeout);
  private_nh.param("result_margin", s.result_margin, s.result_margin);
  private_nh.param("gripper_timeout", s.gripper_timeout, s.gripper_timeout);
  for (double v : {s.connect_timeout, s.result_margin, s.gripper_timeout}) {
    if (!(v > 0.0)) throw Error("the robot's timeouts and margins must be positive seconds");
  }
  return s;
}

struct RosRobot::Impl {
  RosRobotSettings settings;
  // RosRobot serves its own callbacks, so that it works whether or not its caller spins.
  ::ros::CallbackQueue queue;
  ::ros::NodeHandle nh;
  ::ros::AsyncSpinner spinner{1, &queue};
  tf2_ros::Buffer tf;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener;

  LifecycleState state = LifecycleState::kUnconfigured;
  std::map<std::string, std::unique_ptr<ArmClient>> arms;
  std::map<std::string, std::unique_ptr<GripperClient>> grippers;
  std::unique_ptr<HeadClient> head;
  ::ros::Subscriber joint_states;

  mutable std::mutex joints_mutex;
  std::map<std::string, std::pair<double, double>> joints;  // name -> position, velocity
  double joints_stamp = 0.0;
  std::map<std::string, GripperState> last_gripper;  // from the last gripper result

  void receive_joints(const sensor_msgs::JointStateConstPtr& msg) {
    const std::lock_guard<std::mutex> lock(joints_mutex);
    for (std::size_t i = 0; i < msg->name.size() && i < msg->position.size(); ++i) {
      const double v = i < msg->velocity.size() ? msg->velocity[i] : 0.0;
      joints[msg->name[i]] = {msg->position[i], v};
    }
    joints_stamp = msg->header.stamp.toSec();
  }

  bool has_joint_state() const {
    const std::lock_guard<std::mutex> lock(joints_mutex);
    return !joints.empty();
  }
};

RosRobot::RosRobot(::ros::NodeHandle nh, RosRobotSettings settings)
    : impl_(std::make_unique<Impl>()) {
  impl_->settings = std::move(settings);
  // Resolved once: every later use reads the namespaces from here.
  impl_->settings.arm_actions = impl_->settings.resolved_arm_actions();
  impl_->nh = nh;
  impl_->nh.setCallbackQueue(&impl_->queue);
  impl_->spinner.start();
}

RosRobot::~RosRobot() {
  for (auto& [group, arm] : impl_->arms) arm->cancel();
  impl_->spinner.stop();
}

const RosRobotSettings& RosRobot::settings() const { return impl_->settings; }
LifecycleState RosRobot::state() const { return impl_->state; }

CallResult RosRobot::configure() {
  Impl& m = *impl_;
  if (m.state == LifecycleState::kActive) return lifecycle_error("configure", m.state);
  m.arms.clear();
  m.grippers.clear();
  const RosRobotSettings& s = m.settings;
  for (const auto& [group, ns] : s.arm_actions) {
    if (s.arm_action_type == "pr2") {
      m.arms[group] = std::make_unique<Pr2ArmClient>(m.nh, ns);
    } else {
      m.arms[group] = std::make_unique<FollowJointTrajectoryClient>(m.nh, ns);
    }
  }
  for (const auto& [gripper, ns] : s.gripper_actions) {
    m.grippers[gripper] = std::make_unique<GripperClient>(m.nh, ns, false);
  }
  m.head = std::make_unique<HeadClient>(m.nh, s.head_action, false);
  if (!m.tf_listener) m.tf_listener = std::make_unique<tf2_ros::TransformListener>(m.tf);
  {
    const std::lock_guard<std::mutex> lock(m.joints_mutex);
    m.joints.clear();
  }
  m.joint_states = m.nh.subscribe(s.joint_states_topic, 10, &Impl::receive_joints, &m);

  // Every server and the first joint state within one shared deadline.
  const ::ros::WallTime deadline = ::ros::WallTime::now() + ::ros::WallDuration(s.connect_timeout);
  const auto remaining = [&] {
    return std::max(0.01, (deadline - ::ros::WallTime::now()).toSec());
  };
  std::string missing;
  const auto note = [&missing](const std::string& what) {
    missing += (missing.empty() ? "" : ", ") + what;
  };
  for (const auto& [group, ns] : s.arm_actions) {
    if (!m.arms[group]->connect(remaining())) note(ns);
  }
  for (const auto& [gripper, ns] : s.gripper_actions) {
    if (!m.grippers[gripper]->waitForServer(::ros::Duration(remaining()))) note(ns);
  }
  if (!m.head->waitForServer(::ros::Duration(remaining()))) note(s.head_action);
  while (!m.has_joint_state() && ::ros::WallTime::now() < deadline && ::ros::ok()) {
    ::ros::WallDuration(0.01).sleep();
  }
  if (!m.has_joint_state()) note(m.joint_states.getTopic() + " (no joint state)");
  if (!missing.empty()) {
    m.state = LifecycleState::kUnconfigured;
    return CallResult::error("configure: no answer within " + seconds(s.connect_timeout) +
                             " from " + missing);
  }
  m.state = LifecycleState::kInactive;
  return CallResult::success();
}

CallResult RosRobot::activate() {
  if (impl_->state == LifecycleState::kUnconfigured) {
    return lifecycle_error("activate", impl_->state);
  }
  impl_->state = LifecycleState::kActive;
  return CallResult::success();
}

CallResult RosRobot::deactivate() {
  if (impl_->state == LifecycleState::kActive) {
    for (auto& [group, arm] : impl_->arms) arm->cancel();
    for (auto& [gripper, client] : impl_->grippers) client->cancelAllGoals();
    impl_->state = LifecycleState::kInactive;
  }
  return CallResult::success();
}

CallResult RosRobot::read_joint_state(JointState& out) const {
  if (impl_->state == LifecycleState::kUnconfigured) {
    return lifecycle_error("read_joint_state", impl_->state);
  }
  const std::lock_guard<std::mutex> lock(impl_->joints_mutex);
  out = JointState();
  for (const auto& [name, value] : impl_->joints) {
    out.names.push_back(name);
    out.positions.push_back(value.first);
    out.velocities.push_back(value.second);
  }
  out.stamp = impl_->joints_stamp;
  return CallResult::success();
}

CallResult RosRobot::send_trajectory(const std::string& group, const JointTrajectory& trajectory) {
  if (impl_->state != LifecycleState::kActive) {
    return lifecycle_error("send_trajectory", impl_->state);
  }
  const auto it = impl_->arms.find(group);
  if (it == impl_->arms.end()) return CallResult::error("no arm group '" + group + "'");
  if (trajectory.points.empty()) return CallResult::error(group + ": the trajectory is empty");
  const double duration = trajectory.points.back().time_from_start;
  const std::string& what = impl_->settings.arm_actions.at(group);
  return it->second->execute(trajectory, what, duration + impl_->settings.result_margin);
}

CallResult RosRobot::command_gripper(const std::string& gripper, const GripperCommand& command) {
  if (impl_->state != LifecycleState::kActive) {
    return lifecycle_error("command_gripper", impl_->state);
  }
  const auto it = impl_->grippers.find(gripper);
  if (it == impl_->grippers.end()) return CallResult::error("no gripper '" + gripper + "'");
  pr2_controllers_msgs::Pr2GripperCommandGoal goal;
  goal.command.position = command.position;
  goal.command.max_effort =
      command.max_effort < 0.0 ? impl_->settings.gripper_max_effort : command.max_effort;
  GripperClient& client = *it->second;
  client.sendGoal(goal);
  const std::string what = impl_->settings.gripper_actions.at(gripper);
  // The PR2's gripper action aborts when the fingers stall: on an object, that is a grasp.
  CallResult r = wait_for(client, what, impl_->settings.gripper_timeout);
  const auto result = client.getResult();
  if (result && (r.ok() || result->stalled)) {
    GripperState& state = impl_->last_gripper[gripper];
    state.position = result->position;
    state.closed = result->stalled || command.position <= 0.0;
    state.holding_object = result->stalled && result->position > 0.002;
    r = CallResult::success();
  }
  return r;
}

CallResult RosRobot::gripper_state(const std::string& gripper, GripperState& out) const {
  if (impl_->state == LifecycleState::kUnconfigured) {
    return lifecycle_error("gripper_state", impl_->state);
  }
  if (!impl_->settings.gripper_actions.count(gripper)) {
    return CallResult::error("no gripper '" + gripper + "'");
  }
  const auto last = impl_->last_gripper.find(gripper);
  if (last != impl_->last_gripper.end()) {
    out = last->second;
    return CallResult::success();
  }
  // Before any command: the PR2 reports each gripper's opening as the joint {l,r}_gripper_joint.
  const std::lock_guard<std::mutex> lock(impl_->joints_mutex);
  const auto joint = impl_->joints.find(gripper.substr(0, 1) + "_gripper_joint");
  out = GripperState();
  if (joint != impl_->joints.end()) out.position = joint->second.first;
  return CallResult::success();
}

CallResult RosRobot::sensor_pose(Eigen::Isometry3d& T_base_sensor) const {
  if (impl_->state == LifecycleState::kUnconfigured) {
    return lifecycle_error("sensor_pose", impl_->state);
  }
  try {
    T_base_sensor = lookup_pose(impl_->tf, impl_->settings.base_frame, impl_->settings.sensor_frame,
                                ::ros::Time(0), ::ros::Duration(1.0));
  } catch (const Error& e) {
    return CallResult::error(std::string("sensor_pose: ") + e.what());
  }
  return CallResult::success();
}

CallResult RosRobot::point_head(const Eigen::Vector3d& target, double timeout) {
  if (impl_->state != LifecycleState::kActive) return lifecycle_error("point_head", impl_->state);
  pr2_controllers_msgs::PointHeadGoal goal;
  goal.target.header.frame_id = impl_->settings.base_frame;
  goal.target.point.x = target.x();
  goal.target.point.y = target.y();
  goal.target.point.z = target.z();
  goal.pointing_frame = impl_->settings.sensor_frame;
  goal.pointing_axis.z = 1.0;  // an optical frame looks along +z
  goal.min_duration = ::ros::Duration(0.5);
  impl_->head->sendGoal(goal);
  return wait_for(*impl_->head, impl_->settings.head_action, timeout);
}

}  // namespace lmk::ros1
