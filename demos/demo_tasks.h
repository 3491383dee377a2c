// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The paper's six PbD demonstration tasks, end to end on the simulated PR2 (`lmk pbd demo-tasks`):
// for each task, a demonstration scene seen by the head Kinect, landmarks captured with the boxes
// a user would draw, a program recorded by placing the simulated arms, and the paper's test
// scenarios, each planned and executed in a new scene and judged against ground truth.
//
// Success: when a scenario should act, every landmark-relative target is within 2 cm and 10
// degrees of the true target (the true landmark pose, modulo its symmetry, composed with
// T_landmark_ee) and the whole plan executed; when it should not act, the refusal names the
// missing landmark and the robot made no motion. Apart from success, every executed motion is
// checked against the world's ground truth (its objects' meshes) and the robot's own body, and
// what touched is counted (DemoScenarioResult::contacts).

#include <functional>
#include <string>
#include <vector>

#include "lmk/pr2/pr2_motion_check.h"
#include "lmk/search/find_landmark.h"

namespace lmk {

struct DemoScenarioResult {
  int task = 0;
  std::string task_title;
  std::string name;
  bool should_act = true;
  bool success = false;
  std::string reason;  ///< why it succeeded or failed, for a person
  std::size_t steps_executed = 0;
  /// The arm moved for a pose beyond the tolerance, or acted where it should not have: worse than
  /// a refusal (issue #45).
  bool wrong_motion = false;
  bool refused = false;             ///< the plan was refused: nothing moved
  bool stopped = false;             ///< planned, but stopped part way (a watched landmark moved)
  double max_position_error = 0.0;  ///< m, over the landmark-relative targets (acting scenarios)
  double max_rotation_error = 0.0;  ///< rad
  double seconds = 0.0;             ///< perception, planning and execution
  std::size_t looks = 0;            ///< further frames the head took (look_again)
  std::size_t replans = 0;          ///< the program planned again as its landmark moved (watch)
  /// Executed motions that touched the world's ground truth or the robot's own body (issue #60:
  /// SimulatedPr2::contacts), and what the first touched. Counted apart from `success`, which is
  /// the paper's criterion on the targets.
  std::size_t contacts = 0;
  std::string first_contact;
  /// Each motion of the plan acted on that goes around an obstacle: its planning time, s (issue
  /// #60's speed criterion: at most 0.5 s median on the obstacle scenarios).
  std::vector<double> seconds_planning_around;
};

struct DemoTasksReport {
  std::vector<DemoScenarioResult> scenarios;
  double seconds = 0.0;
  std::size_t succeeded() const;
  std::size_t wrong_motions() const;
  std::size_t refusals() const;
  std::size_t contacts() const;  ///< over every scenario
  /// Every scenario's seconds_planning_around, in order.
  std::vector<double> seconds_planning_around() const;
  std::size_t total() const { return scenarios.size(); }
};

struct DemoTasksSettings {
  std::vector<int> tasks;                         ///< 1-6; empty runs all six
  int threads = 0;                                ///< search threads; 0 uses every core
  double min_confidence = kDefaultMinConfidence;  ///< PlanSettings::min_confidence
  /// Further frames the head may take when a landmark is missing or doubtful (pbd/look_again.h);
  /// 0 refuses at once.
  int look_again = 2;
  /// With check_collisions: further frames where a motion would pass through space no camera has
  /// seen (LookAgainSettings::unseen_looks).
  int unseen_looks = 2;
  /// Scenarios whose landmark is moved between two steps run watching it (pbd/watch.h): the move
  /// noticed, the rest re-planned, or the program stopped. false: open loop, as before watching.
  bool watch = true;
  /// Every arm motion checked against the scene the robot planned on and its own body, and planned
  /// around what it would touch, before anything moves (issue #60; PlanSettings::motion_checker).
  /// Off by default for now (docs/pbd.md). Whether on or off, the simulated PR2 checks what its
  /// motions touched against each world's ground truth (DemoScenarioResult::contacts).
  bool check_collisions = false;
  Pr2MotionCheckSettings motion_check;        ///< the check's padding, planning time, unknown space
  double approach = PlanSettings{}.approach;  ///< m along the gripper's axis (PlanSettings)
  double max_position_error = 0.02;           ///< m
  double max_rotation_error = 10.0 * M_PI / 180.0;  ///< rad
  /// If set, each task's landmarks (.lmk) and programs (.json), and every scene (.pcd) are written
  /// there, so that `lmk pbd plan` can replay them.
  std::string save_dir;
  /// A line per stage ("task 1: recording 'pick tool'", "task 1, scenario 2: ...").
  std::function<void(const std::string&)> progress;
  /// If set, each finished task's results are kept in CACHE/demo-tasks/, and a later run with the
  /// same settings and lmk version takes them from there instead of running the task again
  /// (not when save_dir is set: saving needs the run).
  std::string cache_dir;
  /// Polled after each scenario; once it returns true the run stops and run_demo_tasks throws
  /// lmk::Interrupted, naming the tasks kept in the cache.
  std::function<bool()> stop_requested;
};

/// Runs the tasks. Throws lmk::Error only for a broken task definition (a demonstrated pose the
/// arm cannot reach) or an unknown task number; every scenario outcome is in the report.
DemoTasksReport run_demo_tasks(const DemoTasksSettings& settings = {});

/// The paper-style table: task, scenario, should act, success, reason; and the total.
std::string demo_tasks_table(const DemoTasksReport& report);

/// {"scenarios":[{"task":n,"name":"...","should_act":b,"success":b,"reason":"..."}],
///  "succeeded":n,"total":n} with a few more fields per scenario.
std::string demo_tasks_json(const DemoTasksReport& report);

}  // namespace lmk
