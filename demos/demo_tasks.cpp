// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/demos/demo_tasks.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "lmk/demos/detail/demo_moved_landmark.h"
#include "lmk/demos/detail/demo_task_cache.h"
#include "lmk/demos/detail/demo_task_definitions.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/filters.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/geometry/voxel_grid.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/pbd/execute.h"
#include "lmk/pbd/joint_motion.h"
#include "lmk/pbd/look_again.h"
#include "lmk/pbd/plan.h"
#include "lmk/pbd/recorder.h"
#include "lmk/pr2/head_pointing.h"
#include "lmk/pr2/pr2_motion_check.h"
#include "lmk/pr2/pr2_robots.h"
#include "lmk/pr2/simulated_pr2.h"
#include "lmk/search/capture_check.h"

namespace lmk {

namespace {

using detail::DemoArmPose;
using detail::DemoLandmark;
using detail::DemoScenario;
using detail::DemoTask;

void require(const CallResult& r, const std::string& what) {
  if (!r.ok()) throw Error(what + ": " + r.message);
}

std::string task_prefix(const DemoTask& task) { return "task " + std::to_string(task.number); }

// A file name for a landmark or program name: "pick tool" -> "pick_tool".
std::string file_stem(std::string name) {
  std::replace_if(
      name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
  return name;
}

// The PR2 of a task: torso at the task's height, active, its head looking at the task's area.
SimulatedPr2 make_robot(const DemoTask& task) {
  SimulatedPr2 robot = start_simulated_pr2(task.torso_height);
  require(point_head(robot, robot.kinematics(), task.look_at), task_prefix(task) + ": head");
  return robot;
}

PointCloud look(const SimulatedPr2& robot, const DemoWorld& world, std::uint64_t seed) {
  Eigen::Isometry3d T_base_sensor;
  require(robot.sensor_pose(T_base_sensor), "sensor pose");
  return world.observe(T_base_sensor, seed);
}

// The simulated PR2's head and its Kinect in a demo world: pointed by the head's joints, seeing
// the world from where the head's kinematics put the camera, each frame with its own noise.
class HeadKinect : public Eyes {
 public:
  HeadKinect(SimulatedPr2& robot, const DemoWorld& world, std::uint64_t seed)
      : robot_(robot), world_(world), seed_(seed) {}
  CallResult look_at(const Eigen::Vector3d& target, PointCloud& frame) override {
    const CallResult pointed = point_head(robot_, robot_.kinematics(), target);
    if (!pointed.ok()) return pointed;
    frame = look(robot_, world_, ++seed_);
    return CallResult::success();
  }

 private:
  SimulatedPr2& robot_;
  const DemoWorld& world_;
  std::uint64_t seed_;
};

// The box the user draws around a landmark in the demonstration world.
Box drawn_box(const DemoTask& task, const DemoLandmark& l) {
  if (l.object.empty()) return l.box;
  const PlacedObject* o = task.demonstration.object(l.object);
  if (!o) throw Error(task_prefix(task) + ": no object '" + l.object + "' to capture");
  return (l.drawn ? *l.drawn : o->model.part(l.part).box).transformed(o->T_base_object);
}

// Moves one arm to a demonstrated pose the way a person guiding it would end up there, and reads
// back what the robot's FK says, as the recorder would on "save pose".
ArmState place_arm(SimulatedPr2& robot, Arm arm, const DemoArmPose& pose,
                   const std::string& where) {
  const std::string group = arm_group(arm);
  const std::vector<double> from = robot.group_positions(group);
  const IkResult ik = robot.kinematics().inverse(group, pose.T_base_ee, from);
  if (!ik.success) {
    const Eigen::Vector3d p = pose.T_base_ee.translation();
    const Eigen::Vector3d rpy = rpy_from_rotation(pose.T_base_ee.linear()) * 180.0 / M_PI;
    char at[160];
    std::snprintf(at, sizeof(at), " (%.3f, %.3f, %.3f) m, rpy (%.0f, %.0f, %.0f) deg", p.x(), p.y(),
                  p.z(), rpy.x(), rpy.y(), rpy.z());
    throw Error(where + ": the demonstrated pose of the " + arm_name(arm) + " arm" + at +
                " is out of reach: " + ik.message);
  }
  const GroupInfo info = *robot.kinematics().group(group);
  const PlanSettings timing;  // moved at the pace execution would move it
  const double duration = std::max(timing.min_step_duration,
                                   motion_duration(info, from, ik.joints, timing.speed_fraction));
  require(
      robot.send_trajectory(group, joint_line(info, from, ik.joints, duration, timing.waypoints)),
      where);
  GripperCommand g;  // the openings execution commands
  const ExecuteSettings execution;
  g.position =
      pose.gripper == GripperAction::kOpen ? execution.gripper_open : execution.gripper_closed;
  require(robot.command_gripper(arm_gripper(arm), g), where);
  ArmState state;
  require(robot.kinematics().forward(group, robot.group_positions(group), state.T_base_ee), where);
  state.gripper = pose.gripper;
  return state;
}

struct RecordedTask {
  std::map<std::string, Landmark> landmarks;
  std::map<std::string, Program> programs;
};

// Step 1 and 2 of each task: capture the landmarks in the demonstration scene, then record each
// program by placing the simulated arms.
RecordedTask record(const DemoTask& task, const DemoTasksSettings& settings) {
  SimulatedPr2 robot = make_robot(task);
  const PointCloud scene = look(robot, task.demonstration, 1000 + task.number);
  RecordedTask out;
  std::map<std::string, Box> boxes;
  for (const DemoLandmark& l : task.landmarks) {
    CaptureSettings capture_settings;
    capture_settings.base_frame = true;
    capture_settings.allow_flat = l.flat;
    boxes[l.name] = drawn_box(task, l);
    Landmark landmark = capture(scene, boxes[l.name], l.name, capture_settings);
    // The capture check, as `lmk capture` runs it: its findings travel with the landmark into its
    // matches' confidence and the recorder's warnings (issue #59).
    FindSettings check;
    check.scene.up = landmark.up;
    landmark.findings = check_capture(landmark, &scene, check).findings;
    out.landmarks.emplace(l.name, std::move(landmark));
  }
  for (const detail::DemoProgram& p : task.programs) {
    if (settings.progress) settings.progress(task_prefix(task) + ": recording '" + p.name + "'");
    std::vector<ProgramLandmark> declared;
    std::vector<LandmarkInstance> instances;
    for (const std::string& name : p.landmarks) {
      ProgramLandmark pl(name, file_stem(name) + ".lmk");
      pl.symmetry = task.landmark(name).symmetry;
      pl.select = task.landmark(name).select;
      declared.push_back(pl);
      instances.push_back({name, boxes.at(name), out.landmarks.at(name).findings.warnings()});
    }
    Recorder recorder(p.name, declared, instances);
    for (const detail::DemoStep& step : p.steps) {
      std::optional<ArmState> left, right;
      const std::string where = task_prefix(task) + ", program '" + p.name + "'";
      if (step.left) left = place_arm(robot, Arm::kLeft, *step.left, where);
      if (step.right) right = place_arm(robot, Arm::kRight, *step.right, where);
      const std::size_t index = recorder.save_pose(left, right);
      // The user corrects a step the recorder attached to another frame than intended.
      for (Arm arm : {Arm::kLeft, Arm::kRight}) {
        const auto& intended = arm == Arm::kLeft ? step.left : step.right;
        if (intended && recorder.program().steps[index].arm(arm)->frame != intended->frame) {
          recorder.set_frame(index, arm, intended->frame);
        }
      }
    }
    out.programs.emplace(p.name, recorder.program());
  }
  if (!settings.save_dir.empty()) {
    const std::filesystem::path dir =
        std::filesystem::path(settings.save_dir) / ("task" + std::to_string(task.number));
    std::filesystem::create_directories(dir);
    for (const auto& [name, landmark] : out.landmarks) {
      save_landmark((dir / (file_stem(name) + ".lmk")).string(), landmark);
    }
    for (const auto& [name, program] : out.programs) {
      save_program((dir / (file_stem(name) + ".json")).string(), program);
    }
    write_cloud((dir / "demonstration.pcd").string(), scene);
  }
  return out;
}

// The ground-truth boxes of landmark `l` in `world`, with the object each belongs to: the part's
// box, or the user's own box where they drew one instead, moved with the object.
std::vector<std::pair<Box, std::string>> true_boxes(const DemoWorld& world, const DemoLandmark& l) {
  std::vector<std::pair<Box, std::string>> boxes = world.instances(l.name);
  if (l.drawn) {
    for (auto& [box, id] : boxes) box = l.drawn->transformed(world.object(id)->T_base_object);
  }
  return boxes;
}

// The true pose of the landmark instance a plan located: the nearest ground-truth instance turned
// within the landmark's symmetry to the located pose, or for a free-surface patch the valid patch
// under the located one. Nothing when no true instance is there. `object` receives the instance's
// object.
std::optional<Eigen::Isometry3d> true_landmark_pose(const DemoWorld& world, const DemoLandmark& l,
                                                    const LocatedLandmark& located,
                                                    std::string& object) {
  if (world.has_free_surface(l.name)) {
    return world.free_patch_near(l.name, Box(located.T_base_landmark, located.match.box.size));
  }
  std::optional<Eigen::Isometry3d> best;
  double best_distance = 0.05;  // two inches: farther than that, it is no instance of this one
  for (const auto& [box, id] : true_boxes(world, l)) {
    const double d = (box.center() - located.T_base_landmark.translation()).norm();
    if (d < best_distance) {
      best_distance = d;
      best = box.pose;
      best->linear() = nearest_symmetric_rotation(box.pose.linear(),
                                                  located.T_base_landmark.linear(), l.symmetry);
      object = id;
    }
  }
  return best;
}

std::string format_error(double position, double rotation) {
  char text[96];
  std::snprintf(text, sizeof(text), "%.1f mm, %.1f deg", 1000.0 * position,
                rotation * 180.0 / M_PI);
  return text;
}

// Why perception may have failed, from the ground truth: how much of each true instance the head
// Kinect saw, against what the capture saw of the demonstrated one (an instance half hidden behind
// a shelf board shows half the points).
std::string what_the_sensor_saw(const DemoLandmark& l, const DemoWorld& world,
                                const PointCloud& scene, const Landmark& captured) {
  std::string out = "truth:";
  if (world.has_free_surface(l.name)) {
    return out + " no free patch of the table within 3 cm of that place (an object stands in it)";
  }
  const auto instances = true_boxes(world, l);
  if (instances.empty()) return out + " no instance of '" + l.name + "' in the scene";
  for (const auto& [box, id] : instances) {
    const PointCloud inside = voxel_downsample(crop(scene, box), captured.settings.leaf_size);
    const Eigen::Vector3d c = box.center();
    char text[200];
    std::snprintf(text, sizeof(text), " '%s' at (%.3f, %.3f, %.3f) with %zu points seen in its box",
                  l.name.c_str(), c.x(), c.y(), c.z(), inside.size());
    out += text;
  }
  return out + " (the capture had " + std::to_string(captured.points.size()) + ")";
}

// The ground truth the simulated PR2 checks its motions against (issue #60): every object's mesh
// (the floor lies below the arms' reach), built again only when the world has changed.
std::function<std::shared_ptr<const CollisionScene>()> world_truth(const DemoWorld& world) {
  struct Built {
    std::uint64_t revision = 0;
    std::shared_ptr<const CollisionScene> scene;
  };
  auto built = std::make_shared<Built>();
  return [&world, built] {
    if (!built->scene || built->revision != world.revision()) {
      TriangleMesh mesh;
      for (const PlacedObject& o : world.objects()) mesh.append(o.model.mesh, o.T_base_object);
      built->scene = ground_truth_scene(mesh.vertices, mesh.triangles);
      built->revision = world.revision();
    }
    return built->scene;
  };
}

struct ScenarioState {
  DemoWorld world;
  std::optional<SimulatedPr2> robot;
  std::string picked;  ///< the object the last acting scenario's landmark belonged to
};

// Judges an acting scenario's targets against ground truth; returns "" when all are within
// tolerance, else why not.
std::string judge_targets(const DemoTask& task, const Program& program, const Plan& plan,
                          const DemoWorld& world, const DemoTasksSettings& settings,
                          DemoScenarioResult& result, std::string& picked) {
  for (const PlannedStep& step : plan.steps) {
    if (step.phase != Phase::kTarget) continue;  // an approach or retreat: judged by its target's
    for (const PlannedArm& a : step.arms) {
      if (a.frame == kBaseFrame) continue;
      const LocatedLandmark& located = *plan.landmark(a.frame);
      const std::optional<Eigen::Isometry3d> truth =
          true_landmark_pose(world, task.landmark(a.frame), located, picked);
      if (!truth) {
        const Eigen::Vector3d p = located.T_base_landmark.translation();
        char text[200];
        std::snprintf(text, sizeof(text), "'%s' located at (%.3f, %.3f, %.3f), where there is none",
                      a.frame.c_str(), p.x(), p.y(), p.z());
        return text;
      }
      const Eigen::Isometry3d true_target =
          *truth * program.steps[step.index].arm(a.arm)->T_frame_ee;
      result.max_position_error =
          std::max(result.max_position_error,
                   (true_target.translation() - a.T_base_ee.translation()).norm());
      result.max_rotation_error =
          std::max(result.max_rotation_error,
                   rotation_angle_between(true_target.linear(), a.T_base_ee.linear()));
    }
  }
  if (result.max_position_error > settings.max_position_error ||
      result.max_rotation_error > settings.max_rotation_error) {
    return "a target is " + format_error(result.max_position_error, result.max_rotation_error) +
           " from the truth";
  }
  return "";
}

// "; after 2 more looks (...)", or "" without any.
std::string looks_said(const LookedPlan& looked) {
  const std::string said = describe_looks(looked.looks);
  return said.empty() ? "" : "; " + said;
}

// The landmark a refusal names, or "" for an unreachable step.
std::string refused_landmark(const Refusal& refusal) {
  if (const auto* missing = std::get_if<LandmarkNotFound>(&refusal)) return missing->landmark;
  if (const auto* doubtful = std::get_if<LandmarkDoubtful>(&refusal)) return doubtful->landmark;
  return "";
}

// Step 3: one scenario, perceived, planned, executed on the simulated PR2 and judged.
// The scenario's world and robot (those of the previous scenario when it continues it), and the
// head's view of it, saved when the settings say so.
PointCloud set_up_scenario(const DemoTask& task, std::size_t index, ScenarioState& state,
                           const DemoTasksSettings& settings) {
  const DemoScenario& scenario = task.scenarios[index];
  if (scenario.continues_previous && state.robot) {
    if (!state.picked.empty() && state.world.object(state.picked)) state.world.remove(state.picked);
  } else {
    state.world = scenario.world;
    state.robot = make_robot(task);
  }
  state.picked.clear();
  SimulatedPr2& robot = *state.robot;
  robot.contact_world = world_truth(state.world);
  // A scenario that continues the previous one starts from the task's view, wherever the head
  // looked last.
  if (scenario.continues_previous) {
    require(point_head(robot, robot.kinematics(), task.look_at), task_prefix(task) + ": head");
  }
  PointCloud scene = look(robot, state.world, 100 * task.number + index);
  if (!settings.save_dir.empty()) {
    write_cloud((std::filesystem::path(settings.save_dir) / ("task" + std::to_string(task.number)) /
                 ("scenario" + std::to_string(index + 1) + ".pcd"))
                    .string(),
                scene);
  }
  return scene;
}

// What the robot did in a scenario: its plan (after looking again), the execution, the plan the
// arm last followed, the watched run when the landmark was moved, and whether the robot moved.
struct ScenarioRun {
  LookedPlan looked;
  ExecutionReport execution;
  Plan executed;
  std::optional<detail::MovedRun> moved_run;
  bool moved = false;
};

ScenarioRun plan_and_execute(const DemoTask& task, std::size_t index, const RecordedTask& recorded,
                             const PointCloud& scene, ScenarioState& state,
                             const DemoTasksSettings& settings) {
  const DemoScenario& scenario = task.scenarios[index];
  SimulatedPr2& robot = *state.robot;
  const Program& program = recorded.programs.at(scenario.program);
  JointState joints;
  require(robot.read_joint_state(joints), "read joints");
  PlanSettings plan_settings;
  plan_settings.find.execution.threads = settings.threads;
  plan_settings.min_confidence = settings.min_confidence;
  plan_settings.approach = settings.approach;
  if (settings.check_collisions)
    plan_settings.motion_checker = pr2_motion_checker(robot.kinematics(), settings.motion_check);
  HeadKinect eyes(robot, state.world, 100 * (100 * task.number + index));
  LookAgainSettings looking;
  looking.max_looks = settings.look_again;
  looking.unseen_looks = settings.unseen_looks;
  ScenarioRun run{plan_looking_again(program, recorded.landmarks, scene, robot.kinematics(), joints,
                                     eyes, plan_settings, looking),
                  {},
                  {},
                  std::nullopt,
                  false};
  const Plan& plan = run.looked.plan;
  const std::size_t motions_before = robot.history().size();
  const double time_before = robot.time();
  run.executed = plan;  // the plan the arm last followed: a watched move re-plans
  if (scenario.move && plan.valid()) {
    run.moved_run = detail::execute_while_moved(program, plan, robot, state.world, *scenario.move,
                                                recorded.landmarks, settings.watch, plan_settings,
                                                1000 * (100 * task.number + index));
    run.execution = run.moved_run->report;
    run.executed = run.moved_run->executed;
  } else {
    run.execution = execute(plan, robot);
  }
  run.moved = robot.history().size() != motions_before || robot.time() != time_before;
  return run;
}

// The verdict of a scenario the robot should not act in: it refused, naming the missing
// landmark, or (moved while the arm went) stopped with nothing sent after the move.
void judge_refusal(const DemoScenario& scenario, const ScenarioRun& run,
                   DemoScenarioResult& result) {
  const Plan& plan = run.looked.plan;
  const ExecutionReport& execution = run.execution;
  if (run.moved_run) {
    // Carried away while the arm was on its way: stopped, nothing sent after it went.
    result.success = !execution.completed && run.moved_run->sent_after_move == 0;
    result.wrong_motion = run.moved_run->sent_after_move > 0;
    result.reason = result.success
                        ? "stopped: " + execution.error
                        : "moved on towards where '" + scenario.missing_landmark + "' was" +
                              (execution.completed ? " and completed" : ": " + execution.error);
    return;
  }
  // Absent, or present only as a doubtful look-alike: either refusal names the right landmark.
  result.success =
      plan.refusal && refused_landmark(*plan.refusal) == scenario.missing_landmark && !run.moved;
  if (result.success) {
    result.reason = "refused, no motion: " + describe(*plan.refusal) + looks_said(run.looked);
  } else if (plan.valid()) {
    result.wrong_motion = run.moved;
    result.reason = "acted although '" + scenario.missing_landmark + "' is absent";
  } else {
    result.reason = "refused for another reason: " + describe(*plan.refusal);
  }
}

// The verdict of a scenario the robot should act in: every step executed, each target within the
// tolerance of the truth; otherwise why not, with what the sensor saw of the landmarks.
void judge_action(const DemoTask& task, const RecordedTask& recorded, const Program& program,
                  const PointCloud& scene, const ScenarioRun& run, ScenarioState& state,
                  const DemoTasksSettings& settings, DemoScenarioResult& result) {
  const Plan& plan = run.looked.plan;
  const ExecutionReport& execution = run.execution;
  if (!plan.valid()) {
    result.reason = "refused: " + describe(*plan.refusal) + looks_said(run.looked);
    if (const auto* missing = std::get_if<LandmarkNotFound>(&*plan.refusal)) {
      result.reason += "; " + what_the_sensor_saw(task.landmark(missing->landmark), state.world,
                                                  scene, recorded.landmarks.at(missing->landmark));
    }
    return;
  }
  const std::string off =
      judge_targets(task, program, run.executed, state.world, settings, result, state.picked);
  if (!execution.completed) {
    result.reason = "stopped after " + std::to_string(execution.steps_completed) + " of " +
                    std::to_string(plan.steps.size()) + " steps: " + execution.error;
  } else if (!off.empty()) {
    result.wrong_motion = run.moved;
    result.reason = off;
    for (const LocatedLandmark& l : plan.landmarks) {
      result.reason += "; " + what_the_sensor_saw(task.landmark(l.name), state.world, scene,
                                                  recorded.landmarks.at(l.name));
    }
  } else {
    result.success = true;
    result.reason = std::to_string(execution.steps_completed) + " steps executed; targets within " +
                    format_error(result.max_position_error, result.max_rotation_error) +
                    " of the truth";
    if (run.moved_run && !run.moved_run->noticed.empty())
      result.reason += "; " + run.moved_run->noticed[0];
  }
}

// What a scenario's motions touched, counted apart from its success (the paper's criterion, on
// the targets): the first contact leads its reason.
void judge_contacts(const std::vector<ExecutedContact>& contacts, std::size_t before,
                    DemoScenarioResult& result) {
  if (contacts.size() <= before) return;
  result.contacts = contacts.size() - before;
  const ExecutedContact& first = contacts[before];
  result.first_contact = first.group + ": " + describe_touch(first.contact);
  result.reason = "touched (" + result.first_contact + "); " + result.reason;
}

DemoScenarioResult run_scenario(const DemoTask& task, std::size_t index,
                                const RecordedTask& recorded, ScenarioState& state,
                                const DemoTasksSettings& settings) {
  const DemoScenario& scenario = task.scenarios[index];
  const Stopwatch stopwatch;
  DemoScenarioResult result;
  result.task = task.number;
  result.task_title = task.title;
  result.name = scenario.name;
  result.should_act = scenario.should_act;
  const PointCloud scene = set_up_scenario(task, index, state, settings);
  const std::size_t contacts_before = state.robot->contacts().size();
  const ScenarioRun run = plan_and_execute(task, index, recorded, scene, state, settings);
  result.looks = run.looked.looks.size();
  if (run.moved_run) result.replans = run.moved_run->replans;
  result.steps_executed = run.execution.steps_completed;
  for (const PlannedStep& step : run.looked.plan.steps)
    for (const PlannedArm& a : step.arms)
      if (a.planned_around) result.seconds_planning_around.push_back(a.planning_seconds);
  result.refused = !run.looked.plan.valid();
  result.stopped = run.looked.plan.valid() && !run.execution.completed;
  if (!scenario.should_act) {
    judge_refusal(scenario, run, result);
  } else {
    judge_action(task, recorded, recorded.programs.at(scenario.program), scene, run, state,
                 settings, result);
  }
  judge_contacts(state.robot->contacts(), contacts_before, result);
  result.seconds = stopwatch.seconds();
  return result;
}

// What a stopped run says: the tasks it kept, and how to resume.
Interrupted interrupted(const DemoTasksSettings& settings, const std::vector<int>& kept) {
  if (settings.cache_dir.empty()) {
    return Interrupted("demo tasks interrupted; nothing is kept without --cache DIR");
  }
  std::string tasks;
  for (const int t : kept) tasks += (tasks.empty() ? "" : ", ") + std::to_string(t);
  return Interrupted("demo tasks interrupted; " +
                     (kept.empty() ? std::string("no task was finished")
                                   : "tasks " + tasks + " are cached in " + settings.cache_dir +
                                         ": the same command resumes from them"));
}

}  // namespace

DemoTasksReport run_demo_tasks(const DemoTasksSettings& settings) {
  const Stopwatch stopwatch;
  for (const int n : settings.tasks) {
    if (n < 1 || n > 7) throw Error("demo tasks: no task " + std::to_string(n) + " (1 to 7)");
  }
  DemoTasksReport report;
  std::vector<int> kept;  // tasks whose results are in the cache
  for (const DemoTask& task : detail::demo_task_definitions()) {
    if (!settings.tasks.empty() && std::find(settings.tasks.begin(), settings.tasks.end(),
                                             task.number) == settings.tasks.end()) {
      continue;
    }
    const bool saving = !settings.save_dir.empty();
    if (const auto cached = saving ? std::nullopt : read_cached_demo_task(settings, task.number)) {
      if (settings.progress) settings.progress(task_prefix(task) + ": from the cache");
      report.scenarios.insert(report.scenarios.end(), cached->begin(), cached->end());
      kept.push_back(task.number);
      continue;
    }
    const RecordedTask recorded = record(task, settings);
    ScenarioState state;
    std::vector<DemoScenarioResult> results;
    for (std::size_t i = 0; i < task.scenarios.size(); ++i) {
      if (settings.progress) {
        settings.progress(task_prefix(task) + ", scenario " + std::to_string(i + 1) + ": " +
                          task.scenarios[i].name);
      }
      results.push_back(run_scenario(task, i, recorded, state, settings));
      if (settings.stop_requested && settings.stop_requested()) throw interrupted(settings, kept);
    }
    write_cached_demo_task(settings, task.number, results);
    if (!settings.cache_dir.empty()) kept.push_back(task.number);
    report.scenarios.insert(report.scenarios.end(), results.begin(), results.end());
  }
  report.seconds = stopwatch.seconds();
  return report;
}

}  // namespace lmk
