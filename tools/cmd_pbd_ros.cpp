// SPDX-License-Identifier: BSD-3-Clause
// lmk pbd run PROGRAM --ros: a PbD program on a robot under ROS 1 (docs/ros.md, "Run on the PR2").
// The plan is made on the latest camera frame, in the base frame from TF, from the robot's own
// joint state and torso height; when a landmark is missing or doubtful the head looks again (at
// most --look-again further frames, fused with the first); a refusal sends no arm goal at all; a
// controller's abort stops the run and names the step. Ctrl-C cancels the goal under way.

#include <ros/package.h>
#include <ros/ros.h>
#include <tf2_ros/transform_listener.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

#include "lmk/geometry/error.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/landmark/depth_correction_file.h"
#include "lmk/pbd/watch.h"
#include "lmk/pr2/pr2_kinematics.h"
#include "lmk/pr2/pr2_robots.h"
#include "lmk/pr2/srdf.h"
#include "lmk/ros/latest_frame.h"
#include "lmk/ros/ros_eyes.h"
#include "lmk/ros/ros_robot.h"
#include "tools/cli_common.h"
#include "tools/interrupt.h"
#include "tools/pbd_common.h"

namespace lmk::cli {
namespace {

/// Starts this process as a ROS node, or says why it cannot.
void start_ros_node() {
  int argc = 0;
  ros::init(argc, nullptr, "lmk_pbd",
            ros::init_options::NoSigintHandler | ros::init_options::AnonymousName);
  if (!ros::master::check()) {
    throw Error("pbd run --ros: no ROS master at " + ros::master::getURI() +
                " (start roscore, or set ROS_MASTER_URI)");
  }
}

std::shared_ptr<const ros1::Frame> wait_for_frame(const ros1::LatestFrame& latest, double timeout) {
  if (auto frame = latest.wait(timeout)) return frame;
  throw Error("pbd run --ros: no usable frame on " + latest.topic() + " within " +
              std::to_string(static_cast<int>(timeout)) +
              " s (is the camera publishing, and does TF reach the base frame?)");
}

// The plan run watching its landmarks (pbd/watch.h): each look the first camera frame taken after
// the look began (after the motion before it), the landmarks followed by the tracker from where
// the plan found them.
ExecutionReport execute_watched(const Program& program, const Plan& plan,
                                const std::map<std::string, Landmark>& landmarks,
                                const ros1::LatestFrame& latest, RobotInterface& robot,
                                const KinematicsInterface& kinematics, const PbdOptions& o) {
  const PlanSettings planning = plan_settings(o);
  TrackSettings tracking;
  tracking.find = planning.find;
  TrackingWatch watch(
      plan, landmarks,
      [&](PointCloud& frame) {
        const std::shared_ptr<const ros1::Frame> next =
            latest.wait_newer(::ros::Time::now(), o.frame_timeout);
        if (!next) return CallResult::error("no new frame on " + latest.topic());
        frame = next->scene;
        return CallResult::success();
      },
      tracking);
  const WatchedExecution watched =
      execute_watching(program, plan, robot, kinematics, watch, {}, planning);
  for (const std::string& line : watched.noticed) std::printf("watching: %s\n", line.c_str());
  return watched.report;
}

// The robot's collision model for --check-collisions: its robot_description's <collision> shapes
// (meshes found through ROS's package paths), with the pairs of links its
// robot_description_semantic (MoveIt's SRDF) says may touch; or lmk's own PR2 description where
// no robot_description is set.
std::shared_ptr<const RobotBody> robot_description_body() {
  std::string urdf, srdf;
  if (!ros::param::get("robot_description", urdf) || urdf.empty()) {
    std::printf("collision model: lmk's PR2 description (no robot_description parameter)\n");
    return nullptr;
  }
  CollisionShapeSettings shapes;
  shapes.package_path = [](const std::string& name) { return ros::package::getPath(name); };
  try {
    auto model = std::make_shared<RobotModel>(RobotModel::from_string(urdf, "robot_description"));
    std::vector<LinkPair> may_touch;
    if (ros::param::get("robot_description_semantic", srdf) && !srdf.empty())
      may_touch = srdf_disabled_collisions(srdf, "robot_description_semantic");
    auto body = std::make_shared<const RobotBody>(model, shapes, 0.015, may_touch);
    std::printf(
        "collision model: robot_description's %s, %zu collision shapes, %zu pairs of "
        "links that may touch from robot_description_semantic\n",
        model->name().c_str(), body->solids().size(), may_touch.size());
    return body;
  } catch (const Error& e) {
    throw Error(std::string("pbd run --ros: ") + e.what());
  }
}

}  // namespace

int run_on_ros(const PbdOptions& o) {
  const Program program = load_program(o.program);
  const auto landmarks = load_landmarks_of(o, program);
  start_ros_node();
  ros::AsyncSpinner spinner(2);
  spinner.start();
  ros::NodeHandle nh;
  // Settings from the parameter server under /lmk_pbd (docs/ros.md), e.g. arm_action_type.
  const ros1::RosRobotSettings robot_settings =
      ros1::RosRobotSettings::from_parameters(ros::NodeHandle("lmk_pbd"));
  ros1::RosRobot robot(nh, robot_settings);
  tf2_ros::Buffer tf;
  tf2_ros::TransformListener tf_listener(tf);
  const ros1::LatestFrame latest(nh, o.cloud_topic, tf, robot_settings.base_frame, "",
                                 load_depth_correction_if_given(o.depth_correction));
  // The spinner's callbacks use the robot, TF and the camera: on every way out, refusals and errors
  // too, it stops before they go (declared after them, it is destroyed first).
  struct StopSpinning {
    ros::AsyncSpinner& spinner;
    ~StopSpinning() { spinner.stop(); }
  } stop_spinning{spinner};

  const CallResult configured = robot.configure();
  if (!configured.ok()) throw Error("pbd run --ros: " + configured.message);
  const std::shared_ptr<const ros1::Frame> frame = wait_for_frame(latest, o.frame_timeout);
  JointState state;
  const CallResult read = robot.read_joint_state(state);
  if (!read.ok()) throw Error("pbd run --ros: " + read.message);
  const Pr2Kinematics kinematics = pr2_kinematics_at(state);
  std::printf("planning on the frame of %.3f s from %s (%zu points), torso at %.3f m\n",
              frame->stamp.toSec(), o.cloud_topic.c_str(), frame->scene.size(),
              kinematics.torso_height());
  // Looking again points the head, a command: the robot is active from here.
  const CallResult activated = robot.activate();
  if (!activated.ok()) throw Error("pbd run --ros: " + activated.message);
  ros1::RosEyes eyes(robot, latest, o.frame_timeout);
  LookAgainSettings looking;
  looking.max_looks = o.look_again;
  looking.unseen_looks = o.unseen_looks;
  const std::shared_ptr<const RobotBody> body =
      o.check_collisions ? robot_description_body() : nullptr;
  const LookedPlan looked = plan_looking_again(program, landmarks, frame->scene, kinematics, state,
                                               eyes, plan_settings(o, &kinematics, body), looking);
  for (const Look& look : looked.looks) {
    std::printf("looked again at (%.3f, %.3f, %.3f): %s\n", look.target.x(), look.target.y(),
                look.target.z(), look.why.c_str());
  }
  const Plan& plan = looked.plan;
  print_plan(plan);
  if (!plan.valid()) {  // no arm or gripper goal was sent
    robot.deactivate();
    return refused(plan, looked.looks);
  }

  // Ctrl-C: deactivating cancels the goal under way, which ends the run at that step.
  const StopOnSigint sigint;
  std::atomic<bool> done{false};
  std::thread watcher([&] {
    while (!done) {
      if (StopOnSigint::requested()) {
        robot.deactivate();
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  const Stopwatch stopwatch;
  const ExecutionReport report =
      o.watch ? execute_watched(program, plan, landmarks, latest, robot, kinematics, o)
              : execute(plan, robot);
  done = true;
  watcher.join();
  robot.deactivate();
  const double seconds = stopwatch.seconds();
  return report_execution(plan, report, seconds, "wall time");
}

}  // namespace lmk::cli
