// SPDX-License-Identifier: BSD-3-Clause
// lmk pbd show | plan | run | demo-tasks: PbD programs relative to landmarks, planned in a scene,
// executed on the simulated PR2, and the paper's six demonstration tasks end to end.

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "lmk/demos/demo_tasks.h"
#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/landmark/depth_correction_file.h"
#include "lmk/pbd/execute.h"
#include "lmk/pbd/internal/plan_json.h"
#include "lmk/pbd/plan.h"
#include "lmk/pr2/pr2_motion_check.h"
#include "lmk/pr2/pr2_robots.h"
#include "lmk/pr2/simulated_pr2.h"
#include "tools/cli_common.h"
#include "tools/interrupt.h"
#include "tools/pbd_common.h"

namespace lmk::cli {
namespace {

void print_pose(const char* label, const Eigen::Isometry3d& T) {
  const Eigen::Vector3d p = T.translation();
  const Eigen::Vector3d rpy = rpy_degrees(T.linear());
  std::printf("%s(%.3f, %.3f, %.3f) m, rpy (%.1f, %.1f, %.1f) deg", label, p.x(), p.y(), p.z(),
              rpy.x(), rpy.y(), rpy.z());
}

int run_show(const PbdOptions& o) {
  const Program p = load_program(o.program);
  std::printf("program '%s': %zu landmark%s, %zu step%s\n", p.name.c_str(), p.landmarks.size(),
              p.landmarks.size() == 1 ? "" : "s", p.steps.size(), p.steps.size() == 1 ? "" : "s");
  for (const ProgramLandmark& l : p.landmarks) {
    std::printf("  landmark %-16s %s", l.name.c_str(), l.file.c_str());
    if (l.select) std::printf(", policy %s", instance_policy_name(*l.select));
    if (l.symmetry.axis) {
      std::printf(
          ", symmetric about (%.2g, %.2g, %.2g)%s", l.symmetry.axis->x(), l.symmetry.axis->y(),
          l.symmetry.axis->z(),
          l.symmetry.order ? (" " + std::to_string(l.symmetry.order) + "-fold").c_str() : "");
    }
    if (l.demonstration) print_pose(", demonstrated at ", *l.demonstration);
    std::printf("\n");
  }
  for (std::size_t i = 0; i < p.steps.size(); ++i) {
    const ProgramStep& s = p.steps[i];
    std::printf("  step %zu", i);
    if (s.duration) std::printf(" (%.1f s)", *s.duration);
    std::printf("\n");
    for (Arm arm : {Arm::kLeft, Arm::kRight}) {
      if (!s.arm(arm)) continue;
      const ArmTarget& t = *s.arm(arm);
      std::printf("    %-5s in %-14s ", arm_name(arm), t.frame.c_str());
      print_pose("", t.T_frame_ee);
      std::printf(", gripper %s\n", gripper_action_name(t.gripper));
    }
  }
  return kOk;
}

}  // namespace

void print_plan(const Plan& plan) {
  for (const std::string& w : plan.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  for (const LocatedLandmark& l : plan.landmarks) {
    std::printf("landmark %-16s ", l.name.c_str());
    print_pose("at ", l.T_base_landmark);
    std::printf(", error %s, %zu found, %zu eligible (%s)\n",
                format_error(l.match.error, l.metric).c_str(), l.found, l.eligible,
                instance_policy_name(l.policy));
  }
  for (const PlannedStep& s : plan.steps) {
    for (const PlannedArm& a : s.arms) {
      std::printf("step %-3zu %-5s %-8s ", s.index, arm_name(a.arm),
                  s.phase == Phase::kTarget ? "" : phase_name(s.phase));
      print_pose("to ", a.T_base_ee);
      std::printf(", gripper %s, IK %.1e m %.1e rad, %.1f s", gripper_action_name(a.gripper),
                  a.ik.position_error, a.ik.rotation_error, s.duration);
      if (std::isfinite(a.clearance)) {
        std::printf(", clearance %.1f cm%s", 100.0 * a.clearance,
                    a.planned_around ? ", planned around an obstacle" : "");
      }
      std::printf("\n");
    }
  }
}

Pr2MotionCheckSettings motion_check_settings(const PbdOptions& o) {
  Pr2MotionCheckSettings check;
  check.motion.padding = o.padding;
  check.motion.planning_time = o.planning_time;
  check.motion.planning_checks = o.planning_checks;
  check.scene.unknown_is_occupied = o.unknown == "occupied";
  check.scene.unseen_is_occupied = o.unseen == "occupied";
  return check;
}

PlanSettings plan_settings(const PbdOptions& o, const Pr2Kinematics* kinematics,
                           std::shared_ptr<const RobotBody> body) {
  PlanSettings settings;
  if (kinematics && o.check_collisions)
    settings.motion_checker =
        pr2_motion_checker(*kinematics, motion_check_settings(o), std::move(body));
  settings.find.execution.threads = o.threads;
  settings.min_confidence = o.min_confidence;
  settings.approach = o.approach;
  if (!o.policy.empty()) settings.policy = instance_policy_from_name(o.policy);
  if (isatty(STDERR_FILENO)) {
    settings.progress = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
  }
  return settings;
}

std::map<std::string, Landmark> load_landmarks_of(const PbdOptions& o, const Program& program) {
  return load_program_landmarks(program, std::filesystem::path(o.program).parent_path().string());
}

int refused(const Plan& plan, const std::vector<Look>& looks) {
  const std::string after = looks.empty() ? "" : ", " + describe_looks(looks);
  for (const std::string& w : plan.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  std::fprintf(stderr, "lmk: refused: %s%s\n", describe(*plan.refusal).c_str(), after.c_str());
  return kInternalError;  // exit 1: a valid request the robot will not carry out
}

int report_execution(const Plan& plan, const ExecutionReport& report, double seconds,
                     const char* clock) {
  for (const std::string& line : report.log) std::printf("executed %s\n", line.c_str());
  if (!report.completed) {
    std::fprintf(stderr, "lmk: stopped after %zu of %zu steps: %s\n", report.steps_completed,
                 report.steps_total, report.error.c_str());
    return kInternalError;
  }
  std::printf("program '%s' done: %zu steps in %.1f s of %s\n", plan.program.c_str(),
              report.steps_completed, seconds, clock);
  return kOk;
}

namespace {

// Plans the program in the scene for the simulated PR2 at rest (start_simulated_pr2(o.torso)), so
// that `run` can execute the plan on it.
Plan plan_program(const PbdOptions& o, SimulatedPr2& robot) {
  format_from_path(o.scene);
  const Program program = load_program(o.program);
  const auto landmarks = load_landmarks_of(o, program);
  PointCloud scene = read_cloud(o.scene);
  correct_depth(scene, o.depth_correction);
  JointState state;
  robot.read_joint_state(state);
  return plan(program, landmarks, scene, robot.kinematics(), state,
              plan_settings(o, &robot.kinematics()));
}

int run_plan(const PbdOptions& o) {
  SimulatedPr2 robot = start_simulated_pr2(o.torso);
  const Plan plan = plan_program(o, robot);
  if (o.json_stdout) {
    std::cout << detail::plan_to_json(plan).dump(2) << "\n";
  } else {
    print_plan(plan);
  }
  return plan.valid() ? kOk : refused(plan);
}

int run_run(const PbdOptions& o) {
  if (o.ros && !o.scene.empty()) {
    throw Error("pbd run --ros: --scene does not apply; the robot's camera gives the frame");
  }
  if (o.ros) return run_on_ros(o);
  if (o.look_again_given) {
    throw Error(
        "pbd run --sim: --look-again and --unseen-looks need a head that turns: with --ros (the "
        "simulated run plans on one fixed --scene)");
  }
  if (o.watch) {
    throw Error(
        "pbd run --sim: --watch needs a camera that keeps looking: with --ros (the simulated "
        "run has one fixed --scene; lmk pbd demo-tasks shows watching on the simulated PR2)");
  }
  if (!o.sim || o.scene.empty()) {
    throw Error(
        "pbd run: give --sim --scene FILE for the simulated PR2, or --ros for a robot "
        "under ROS 1");
  }
  SimulatedPr2 robot = start_simulated_pr2(o.torso);
  const Plan plan = plan_program(o, robot);
  print_plan(plan);
  if (!plan.valid()) return refused(plan);
  const ExecutionReport report = execute(plan, robot);
  return report_execution(plan, report, robot.time(), "robot time");
}

int run_demo_tasks_command(const PbdOptions& o) {
  DemoTasksSettings settings;
  settings.tasks = o.tasks;
  settings.threads = o.threads;
  settings.min_confidence = o.min_confidence;
  settings.look_again = o.look_again;
  settings.unseen_looks = o.unseen_looks;
  settings.watch = !o.no_watch;
  settings.check_collisions = o.check_collisions;
  settings.motion_check = motion_check_settings(o);
  settings.approach = o.approach;
  settings.save_dir = o.save_dir;
  settings.cache_dir = o.cache_dir;
  const StopOnSigint stop;
  settings.stop_requested = &StopOnSigint::requested;
  // One line per scenario on stderr: a run takes a minute or two.
  settings.progress = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
  const DemoTasksReport report = run_demo_tasks(settings);
  std::printf("%s", demo_tasks_table(report).c_str());
  if (!o.json.empty()) {
    const nlohmann::json j = json_output(nlohmann::json::parse(demo_tasks_json(report)), o.timings);
    write_text_atomically(o.json, j.dump(2) + "\n");
  }
  return kOk;
}

// Issue #60: every arm motion checked against the scene and the robot before anything moves.
void add_collision_options(CLI::App* sub, PbdOptions& o) {
  sub->add_flag("--check-collisions,!--no-check-collisions", o.check_collisions,
                "Check every motion against the scene, the space it hides and the robot, plan "
                "around what it would touch, or refuse (on by default; --no-check-collisions "
                "moves along straight joint lines unchecked, as before issue #60)");
  sub->add_option("--padding", o.padding, "Distance kept from the scene and the robot, m")
      ->check(CLI::Range(kMinPadding, kMaxPadding))
      ->capture_default_str();
  sub->add_option("--planning-time", o.planning_time,
                  "Seconds to find a path around an obstacle before refusing")
      ->check(CLI::Range(0.01, 60.0))
      ->capture_default_str();
  sub->add_option("--planning-checks", o.planning_checks,
                  "Configurations a path around an obstacle may check before refusing: the "
                  "budget that does not depend on the machine (the same inputs, the same path)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{100000000}))
      ->capture_default_str();
  sub->add_option("--unknown", o.unknown,
                  "The space the sensor could not see: 'occupied' (the arm never sweeps through "
                  "it) or 'free'")
      ->check(CLI::IsMember({"occupied", "free"}))
      ->capture_default_str();
  sub->add_option("--unseen", o.unseen,
                  "The space no camera had in view: 'look' (the head looks where a motion would "
                  "pass through it; what stays unseen is a warning) or 'occupied' (the arm never "
                  "goes there: from one head view, most motions are refused)")
      ->check(CLI::IsMember({"look", "occupied"}))
      ->capture_default_str();
  sub->add_option("--approach", o.approach,
                  "Reach a grasp from this far back along the gripper's axis, fingers open, and "
                  "back off a release as far, m; a program's own approach counts (0: none)")
      ->check(CLI::Range(0.0, kMaxApproach))
      ->capture_default_str();
}

void add_plan_options(CLI::App* sub, PbdOptions& o, bool scene_required) {
  sub->add_option("program", o.program, "Program file (.json)")->required();
  CLI::Option* scene =
      sub->add_option("--scene", o.scene, "Scene cloud in the robot base frame (.pcd, .ply, .xyz)");
  if (scene_required) scene->required();
  add_depth_correction_option(sub, o.depth_correction);
  sub->add_option("--torso", o.torso, "PR2 torso height, m (0 to 0.33)")->capture_default_str();
  sub->add_option("--policy", o.policy,
                  "Instance policy for landmarks whose program sets none: best-error, "
                  "nearest-to-demonstration, demonstrated-height");
  sub->add_option("--min-confidence", o.min_confidence,
                  "Least confidence of a landmark to act on (0 to 1); below it the program is "
                  "refused before anything moves (0: act on any match)")
      ->check(within(0.0, 1.0))
      ->capture_default_str();
  sub->add_option("--threads", o.threads, "Search threads; 0 uses every core")
      ->check(worker_threads())
      ->capture_default_str();
  add_collision_options(sub, o);
}

void add_look_again_option(CLI::App* sub, PbdOptions& o, const std::string& what) {
  sub->add_option("--look-again", o.look_again,
                  what +
                      " the head may take, pointed where they can settle it, when a landmark is "
                      "missing or doubtful, before refusing (0: refuse at once)")
      ->check(CLI::Range(0, 8))
      ->capture_default_str()
      ->each([&o](const std::string&) { o.look_again_given = true; });
  sub->add_option("--unseen-looks", o.unseen_looks,
                  "With --check-collisions: further frames the head may take where a motion would "
                  "pass through space no camera has seen, before acting on what it saw")
      ->check(CLI::Range(0, 8))
      ->capture_default_str()
      ->each([&o](const std::string&) { o.look_again_given = true; });
}

}  // namespace

Subcommand add_pbd(CLI::App& app) {
  auto o = std::make_shared<PbdOptions>();
  CLI::App* sub = app.add_subcommand("pbd", "PbD programs: show, plan, run, the paper's six tasks");
  sub->require_subcommand(1);
  CLI::App* show = sub->add_subcommand("show", "Print a program's landmarks and steps");
  show->add_option("program", o->program, "Program file (.json)")->required();
  CLI::App* plan = sub->add_subcommand(
      "plan", "Locate the landmarks, compose the targets and solve IK, or say why not");
  add_plan_options(plan, *o, true);
  plan->add_flag("--json", o->json_stdout, "Print the plan (or refusal) as JSON");
  CLI::App* run = sub->add_subcommand(
      "run", "Plan, then execute on the simulated PR2 (--sim) or a robot under ROS 1 (--ros)");
  add_plan_options(run, *o, false);
  CLI::Option* sim = run->add_flag("--sim", o->sim, "Execute on the simulated PR2 (needs --scene)");
  CLI::Option* ros = run->add_flag(
      "--ros", o->ros,
      "Execute on a robot under ROS 1 (the PR2's controllers; docs/ros.md): plan on the latest "
      "camera frame, in the base frame from TF");
  sim->excludes(ros);
  run->add_option("--cloud-topic", o->cloud_topic, "With --ros: the camera's cloud topic")
      ->capture_default_str();
  run->add_option("--frame-timeout", o->frame_timeout,
                  "With --ros: seconds to wait for a camera frame and the robot")
      ->capture_default_str();
  add_look_again_option(run, *o, "With --ros: further frames");
  run->add_flag("--watch", o->watch,
                "With --ros: before every step and every grasp or release, follow the landmarks "
                "in the camera's frames; one moved beyond 1 cm or 5 degrees re-plans the rest, a "
                "lost one stops the run (docs/pbd.md)");
  CLI::App* demo = sub->add_subcommand(
      "demo-tasks", "The paper's six demonstration tasks, end to end on the simulated PR2");
  demo->add_option("--json", o->json, "Also write the results as JSON to FILE");
  add_timings_flag(demo, o->timings);
  demo->add_option("--task", o->tasks, "Only these tasks (1 to 6: the paper's; 7: obstacles)");
  demo->add_option("--min-confidence", o->min_confidence,
                   "Least confidence of a landmark to act on (0 to 1; 0: act on any match)")
      ->check(within(0.0, 1.0))
      ->capture_default_str();
  add_look_again_option(demo, *o, "Further frames");
  demo->add_flag("--no-watch", o->no_watch,
                 "Run the scenarios whose landmark moves between two steps open loop, as before "
                 "programs watched their landmarks (issue #48)");
  demo->add_option("--save", o->save_dir,
                   "Write each task's landmarks, programs and scenes to DIR/taskN");
  demo->add_option("--threads", o->threads, "Search threads; 0 uses every core")
      ->check(worker_threads())
      ->capture_default_str();
  add_collision_options(demo, *o);
  demo->add_option("--cache", o->cache_dir,
                   "Keep each finished task's results in DIR; a later run (after Ctrl-C, say) "
                   "takes them from there");
  return {sub, [o, show, plan, run] {
            if (show->parsed()) return run_show(*o);
            if (plan->parsed()) return run_plan(*o);
            if (run->parsed()) return run_run(*o);
            return run_demo_tasks_command(*o);
          }};
}

}  // namespace lmk::cli
