// SPDX-License-Identifier: BSD-3-Clause
#include "tests/ros/support/fake_pr2.h"

#include <actionlib/server/simple_action_server.h>
#include <pr2_controllers_msgs/JointTrajectoryAction.h>
#include <pr2_controllers_msgs/PointHeadAction.h>
#include <pr2_controllers_msgs/Pr2GripperCommandAction.h>
#include <ros/callback_queue.h>
#include <ros/spinner.h>
#include <sensor_msgs/JointState.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/transform_broadcaster.h>

#include <algorithm>
#include <atomic>
#include <thread>

#include "lmk/pr2/pr2_kinematics.h"
#include "lmk/pr2/simulated_pr2.h"
#include "lmk/ros/cloud_conversion.h"

namespace lmk::test {
namespace {

using ArmServer = actionlib::SimpleActionServer<pr2_controllers_msgs::JointTrajectoryAction>;
using GripperServer = actionlib::SimpleActionServer<pr2_controllers_msgs::Pr2GripperCommandAction>;
using HeadServer = actionlib::SimpleActionServer<pr2_controllers_msgs::PointHeadAction>;

constexpr double kGripperMaxOpening = 0.09;  // m, as SimulatedPr2

}  // namespace

struct FakePr2::Impl {
  FakePr2Settings settings;
  Pr2Kinematics kinematics;
  // The servers' callbacks run on this queue, spun by `spinner`, which ~Impl stops before the
  // servers go. On the process's global queue a cancel could still reach a server being destroyed
  // (RosRobot's destructor cancels its goals), and roscpp then aborted publishing the server's
  // status on a topic already unadvertised ('null Publication').
  ::ros::CallbackQueue queue;
  ::ros::NodeHandle nh;
  ::ros::AsyncSpinner spinner{2, &queue};
  mutable std::mutex mutex;
  std::map<std::string, double> joints;
  std::map<std::string, int> goal_counts;
  std::map<std::string, std::vector<trajectory_msgs::JointTrajectory>> trajectories;
  int arm_goals = 0, abort_at = 0, hang_at = 0, cancelled = 0;
  std::vector<std::unique_ptr<ArmServer>> arms;
  std::vector<std::unique_ptr<GripperServer>> grippers;
  std::unique_ptr<HeadServer> head;
  ::ros::Publisher joint_states, cloud;
  sensor_msgs::PointCloud2 cloud_msg;
  tf2_ros::TransformBroadcaster tf;
  std::atomic<bool> running{true};
  std::thread publisher;

  explicit Impl(FakePr2Settings s)
      : settings(std::move(s)), kinematics(RobotModel::pr2(), settings.torso_height) {
    nh.setCallbackQueue(&queue);
    // Every joint at zero, or at the nearest limit, then the arms at the robot's sides, as
    // SimulatedPr2 starts.
    for (const std::string& group : kinematics.groups()) {
      const GroupInfo info = *kinematics.group(group);
      for (const JointInfo& j : info.joints) {
        joints[j.name] = j.continuous() ? 0.0 : std::clamp(0.0, j.lower, j.upper);
      }
    }
    for (const auto& [name, value] : pr2_arms_at_sides()) joints[name] = value;
    joints["torso_lift_joint"] = settings.torso_height;
    joints["l_gripper_joint"] = joints["r_gripper_joint"] = kGripperMaxOpening;
    cloud_msg = camera_message(settings.scene);

    for (const char* side : {"l", "r"}) {
      const std::string arm_ns = std::string(side) + "_arm_controller/joint_trajectory_action";
      arms.push_back(std::make_unique<ArmServer>(
          nh, arm_ns, [this, arm_ns](const auto& goal) { execute_arm(arm_ns, goal); }, false));
      const std::string grip_ns = std::string(side) + "_gripper_controller/gripper_action";
      const std::string joint = std::string(side) + "_gripper_joint";
      grippers.push_back(std::make_unique<GripperServer>(
          nh, grip_ns,
          [this, grip_ns, joint](const auto& goal) { execute_gripper(grip_ns, joint, goal); },
          false));
    }
    head = std::make_unique<HeadServer>(
        nh, "head_traj_controller/point_head_action",
        [this](const auto&) {
          count("head_traj_controller/point_head_action");
          turn_head();
          head->setSucceeded();
        },
        false);
    for (auto& s : arms) s->start();
    for (auto& s : grippers) s->start();
    head->start();
    joint_states = nh.advertise<sensor_msgs::JointState>("joint_states", 10);
    cloud = nh.advertise<sensor_msgs::PointCloud2>(settings.cloud_topic, 1);
    publisher = std::thread([this] { publish_loop(); });
    spinner.start();
  }

  ~Impl() {
    running = false;  // ends publish_loop and a held goal
    publisher.join();
    spinner.stop();  // waits for the callbacks running now; later messages only queue
    for (auto& s : arms) s->shutdown();
    for (auto& s : grippers) s->shutdown();
    head->shutdown();
  }

  void count(const std::string& ns) {
    const std::lock_guard<std::mutex> lock(mutex);
    ++goal_counts[ns];
  }

  /// A cloud of the head Kinect as the camera publishes it: in its optical frame.
  sensor_msgs::PointCloud2 camera_message(const PointCloud& scene) const {
    return ros1::to_ros(scene.transformed(settings.scene.T_cloud_sensor.inverse()),
                        settings.sensor_frame);
  }

  // The camera's view after the head goal just counted. It changes before the goal succeeds, so a
  // frame stamped after the client heard of that shows the new view.
  void turn_head() {
    const std::vector<PointCloud>& after = settings.scenes_after_head_goals;
    if (after.empty()) return;
    const std::lock_guard<std::mutex> lock(mutex);
    const std::size_t k =
        static_cast<std::size_t>(goal_counts["head_traj_controller/point_head_action"]);
    cloud_msg = camera_message(after[std::min(k, after.size()) - 1]);
  }

  void execute_arm(const std::string& ns,
                   const pr2_controllers_msgs::JointTrajectoryGoalConstPtr& goal) {
    bool abort = false, hang = false;
    {
      const std::lock_guard<std::mutex> lock(mutex);
      ++goal_counts[ns];
      trajectories[ns].push_back(goal->trajectory);
      abort = ++arm_goals == abort_at;
      hang = arm_goals == hang_at;
      const std::vector<PointCloud>& after = settings.scenes_after_arm_goals;
      if (!after.empty()) {
        cloud_msg = camera_message(after[std::min<std::size_t>(arm_goals, after.size()) - 1]);
      }
      abort = abort || hang;  // a held goal moves nothing
      // A real controller runs the trajectory; the fake jumps to its end at once.
      if (!abort && !goal->trajectory.points.empty()) {
        const auto& last = goal->trajectory.points.back().positions;
        for (std::size_t i = 0; i < goal->trajectory.joint_names.size() && i < last.size(); ++i) {
          joints[goal->trajectory.joint_names[i]] = last[i];
        }
      }
    }
    ArmServer& server = *arms[ns[0] == 'l' ? 0 : 1];
    if (hang) {
      // Held until the client gives up and cancels, as a stuck controller would.
      while (running && !server.isPreemptRequested()) ::ros::WallDuration(0.01).sleep();
      {
        const std::lock_guard<std::mutex> lock(mutex);
        ++cancelled;
      }
      server.setPreempted();
      return;
    }
    if (abort) {
      server.setAborted(pr2_controllers_msgs::JointTrajectoryResult(),
                        "fake PR2: the test asked for an abort");
    } else {
      server.setSucceeded();
    }
  }

  void execute_gripper(const std::string& ns, const std::string& joint,
                       const pr2_controllers_msgs::Pr2GripperCommandGoalConstPtr& goal) {
    pr2_controllers_msgs::Pr2GripperCommandResult result;
    {
      const std::lock_guard<std::mutex> lock(mutex);
      ++goal_counts[ns];
      joints[joint] = std::clamp(goal->command.position, 0.0, kGripperMaxOpening);
      result.position = joints[joint];
    }
    result.reached_goal = true;
    grippers[ns[0] == 'l' ? 0 : 1]->setSucceeded(result);
  }

  geometry_msgs::TransformStamped transform(const Eigen::Isometry3d& T, const std::string& child,
                                            const ::ros::Time& stamp) {
    geometry_msgs::TransformStamped t = tf2::eigenToTransform(T);
    t.header.frame_id = "base_link";
    t.header.stamp = stamp;
    t.child_frame_id = child;
    return t;
  }

  // /joint_states and TF at 50 Hz, the cloud at settings.cloud_rate, all stamped alike so that the
  // node finds TF at the cloud's own stamp.
  void publish_loop() {
    ::ros::WallRate rate(50.0);
    const int cloud_every = std::max(1, static_cast<int>(50.0 / settings.cloud_rate));
    for (int tick = 0; running; ++tick) {
      const ::ros::Time now = ::ros::Time::now();
      sensor_msgs::JointState state;
      std::vector<geometry_msgs::TransformStamped> transforms;
      {
        const std::lock_guard<std::mutex> lock(mutex);
        state.header.stamp = now;
        for (const auto& [name, q] : joints) {
          state.name.push_back(name);
          state.position.push_back(q);
          state.velocity.push_back(0.0);
        }
        transforms.push_back(transform(kinematics.T_base_torso(), "torso_lift_link", now));
        transforms.push_back(transform(settings.scene.T_cloud_sensor, settings.sensor_frame, now));
        for (const auto& [group, tool] :
             {std::pair<std::string, std::string>{"left_arm", "l_gripper_tool_frame"},
              {"right_arm", "r_gripper_tool_frame"}}) {
          std::vector<double> q;
          const GroupInfo info = *kinematics.group(group);  // alive while its joints are read
          for (const JointInfo& j : info.joints) q.push_back(joints[j.name]);
          Eigen::Isometry3d T_base_tool;
          if (kinematics.forward(group, q, T_base_tool).ok()) {
            transforms.push_back(transform(T_base_tool, tool, now));
          }
        }
      }
      joint_states.publish(state);
      tf.sendTransform(transforms);
      if (tick % cloud_every == 0) {
        sensor_msgs::PointCloud2 msg;
        {
          const std::lock_guard<std::mutex> lock(mutex);
          msg = cloud_msg;
        }
        msg.header.stamp = now;
        cloud.publish(msg);
      }
      rate.sleep();
    }
  }
};

FakePr2::FakePr2(FakePr2Settings settings) : impl_(std::make_unique<Impl>(std::move(settings))) {}
FakePr2::~FakePr2() = default;

int FakePr2::goals(const std::string& ns) const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  const auto it = impl_->goal_counts.find(ns);
  return it == impl_->goal_counts.end() ? 0 : it->second;
}

int FakePr2::total_goals() const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  int total = 0;
  for (const auto& [ns, n] : impl_->goal_counts) total += n;
  return total;
}

std::vector<trajectory_msgs::JointTrajectory> FakePr2::trajectories(const std::string& ns) const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  const auto it = impl_->trajectories.find(ns);
  return it == impl_->trajectories.end() ? std::vector<trajectory_msgs::JointTrajectory>{}
                                         : it->second;
}

void FakePr2::abort_arm_goal(int n) {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->abort_at = n;
}

void FakePr2::hang_arm_goal(int n) {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->hang_at = n;
}

int FakePr2::cancelled_goals() const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->cancelled;
}

std::map<std::string, double> FakePr2::joints() const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->joints;
}

}  // namespace lmk::test
