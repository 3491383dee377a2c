// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What lmk pbd's simulated and ROS runs share (tools/cmd_pbd.cpp, tools/cmd_pbd_ros.cpp): the
// options, the planner's settings, and how plans, refusals and executions are printed.

#include <map>
#include <string>
#include <vector>

#include "lmk/pbd/execute.h"
#include "lmk/pbd/look_again.h"
#include "lmk/pbd/plan.h"
#include "lmk/pr2/pr2_motion_check.h"

namespace lmk::cli {

struct PbdOptions {
  std::string program, scene, json, save_dir, policy, cache_dir;
  std::string depth_correction;  ///< a file of lmk calibrate-depth, for the scene or the camera
  double torso = 0.0;
  int threads = 0;
  double min_confidence = kDefaultMinConfidence;  ///< PlanSettings::min_confidence
  /// demo-tasks and run --ros: further frames when a landmark is missing or doubtful
  int look_again = 2;
  bool look_again_given = false;  ///< --look-again was on the command line
  bool no_watch = false;          ///< demo-tasks: moved landmarks open loop, unwatched
  bool watch = false;             ///< run --ros: watch the landmarks while the program runs
  bool sim = false, ros = false, json_stdout = false, timings = false;
  std::vector<int> tasks;
  std::string cloud_topic = "/head_mount_kinect/depth_registered/points";
  double frame_timeout = 10.0;  ///< s
  /// Issue #60: every motion checked against the scene and the robot (--check-collisions, the
  /// default; --no-check-collisions turns it off)
  bool check_collisions = true;
  double padding = 0.02;                                                ///< --padding, m
  double planning_time = 2.0;                                           ///< --planning-time, s
  std::size_t planning_checks = MotionCheckSettings{}.planning_checks;  ///< --planning-checks
  std::string unknown = "occupied";  ///< --unknown: the space the sensor could not see
  /// --unseen: the space no camera had in view, "look" (looked at first, else acted on with a
  /// warning) or "occupied" (never passed through)
  std::string unseen = "look";
  int unseen_looks = 2;  ///< --unseen-looks: demo-tasks and run --ros, where motions go unseen
  double approach = PlanSettings{}.approach;  ///< --approach, m
};

/// The planner's settings; with `kinematics` and --check-collisions, every motion checked for the
/// PR2 it describes.
/// `body`: the robot's collision model (unset: lmk's PR2 description's).
PlanSettings plan_settings(const PbdOptions& o, const Pr2Kinematics* kinematics = nullptr,
                           std::shared_ptr<const RobotBody> body = nullptr);
/// --padding, --planning-time, --unknown as the PR2's motion check takes them.
Pr2MotionCheckSettings motion_check_settings(const PbdOptions& o);
/// The program's landmarks, their files relative to the program's folder.
std::map<std::string, Landmark> load_landmarks_of(const PbdOptions& o, const Program& program);
void print_plan(const Plan& plan);
/// Prints the refusal, naming the further looks taken before it; the exit code of a refused run.
int refused(const Plan& plan, const std::vector<Look>& looks = {});
/// Prints what was executed, or where it stopped and why; the exit code. `seconds` of `clock`
/// ("robot time", "wall time") is the run's duration.
int report_execution(const Plan& plan, const ExecutionReport& report, double seconds,
                     const char* clock);

/// lmk pbd run --ros: plans on the robot's latest frame and executes through RosRobot. Without ROS
/// (LMK_WITH_ROS=OFF) it throws lmk::Error saying so.
int run_on_ros(const PbdOptions& o);

}  // namespace lmk::cli
