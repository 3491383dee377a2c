// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pbd/plan.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numeric>

#include "lmk/geometry/error.h"
#include "lmk/geometry/random.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/pbd/detail/locate_landmarks.h"
#include "lmk/pbd/joint_motion.h"
#include "lmk/search/scene_index.h"

namespace lmk {

namespace {
constexpr int kTargetRetries = 16;  // IK seeds tried for a target that touches something
constexpr std::uint64_t kTargetSeed = 60;

// "step 3, right arm", "step 3's approach, right arm".
std::string motion_name(std::size_t step, Phase phase, Arm arm) {
  return step_name(step, phase) + ", " + arm_name(arm) + " arm";
}
}  // namespace

const char* refusal_kind(const Refusal& refusal) {
  if (std::holds_alternative<LandmarkNotFound>(refusal)) return "landmark-not-found";
  if (std::holds_alternative<LandmarkDoubtful>(refusal)) return "landmark-doubtful";
  if (std::holds_alternative<Blocked>(refusal)) return "collision";
  return "unreachable";
}

std::string describe(const Refusal& refusal) {
  if (const auto* missing = std::get_if<LandmarkNotFound>(&refusal)) {
    return "landmark '" + missing->landmark + "' not found: " + missing->reason;
  }
  if (const auto* doubtful = std::get_if<LandmarkDoubtful>(&refusal)) {
    char text[96];
    if (std::isnan(doubtful->confidence)) {
      std::snprintf(text, sizeof(text), "no confidence (no calibration for the metric), cut %.2f",
                    doubtful->min_confidence);
    } else {
      std::snprintf(text, sizeof(text), "confidence %.2f below %.2f", doubtful->confidence,
                    doubtful->min_confidence);
    }
    return "landmark '" + doubtful->landmark + "' doubtful: " + text +
           (doubtful->doubt.empty() ? "" : ": " + doubtful->doubt);
  }
  if (const auto* blocked = std::get_if<Blocked>(&refusal)) {
    return motion_name(blocked->step, blocked->phase, blocked->arm) + ": " +
           describe(blocked->contact) + "; " + blocked->planner;
  }
  const auto& u = std::get<Unreachable>(refusal);
  return motion_name(u.step, u.phase, u.arm) + ": unreachable: " + u.reason;
}

const LocatedLandmark* Plan::landmark(const std::string& name) const {
  for (const LocatedLandmark& l : landmarks) {
    if (l.name == name) return &l;
  }
  return nullptr;
}

std::map<std::string, Landmark> load_program_landmarks(const Program& program,
                                                       const std::string& program_dir) {
  std::map<std::string, Landmark> out;
  for (const ProgramLandmark& l : program.landmarks) {
    std::filesystem::path file(l.file);
    if (file.is_relative() && !program_dir.empty())
      file = std::filesystem::path(program_dir) / file;
    try {
      out.emplace(l.name, load_landmark(file.string()));
    } catch (const Error& e) {
      throw Error("program '" + program.name + "', landmark '" + l.name + "': " + e.what());
    }
  }
  return out;
}

namespace {

// Steps 1-2: locating the landmarks (detail/locate_landmarks.h).
using detail::Candidates;
using detail::choose;
using detail::locate_landmarks;

// The arms' groups and their joints at the start.
struct Arms {
  std::map<Arm, GroupInfo> groups;
  std::map<Arm, std::vector<double>> start;
};

// The step and arm a step's refusal names.
std::pair<std::size_t, Arm> step_arm(const Refusal& r) {
  if (const auto* b = std::get_if<Blocked>(&r)) return {b->step, b->arm};
  const auto& u = std::get<Unreachable>(r);
  return {u.step, u.arm};
}

// The arm a contact's link belongs to (the PR2's "l_"/"r_" names), else `fallback`.
Arm arm_of(const std::string& link, Arm fallback) {
  if (link.rfind("l_", 0) == 0) return Arm::kLeft;
  if (link.rfind("r_", 0) == 0) return Arm::kRight;
  return fallback;
}

// `q`, in the group's order, into `joints` by name.
void set_joints(const GroupInfo& group, const std::vector<double>& q, JointValues& joints) {
  for (std::size_t i = 0; i < group.joints.size(); ++i) joints[group.joints[i].name] = q[i];
}

// One arm's motion with every other joint held as in `from`: its straight line when free, else a
// path around what the line would touch; the waypoints after the start, the goal last.
struct ArmMotion {
  std::vector<std::vector<double>> waypoints;
  double clearance = 0.0;
  bool around = false;
  double planning_seconds = 0.0;  ///< spent on the path around, found or not
  std::size_t planning_checks = 0;
  std::optional<MotionContact> contact;  ///< what the line would touch, when no path was found
  std::string why;                       ///< the planner's reason then
};

ArmMotion move_arm(const MotionChecker& checker, const GroupInfo& group, const JointValues& from,
                   const std::vector<double>& goal, const IntendedContact& intended) {
  JointValues to;
  set_joints(group, goal, to);
  ArmMotion m;
  const MotionVerdict line = checker.check_line(from, to, intended);
  m.clearance = line.clearance;
  if (line.free()) {
    m.waypoints = {goal};
    return m;
  }
  const MotionPlan around = checker.plan_around(group.name, from, to, intended);
  m.planning_seconds = around.seconds;
  m.planning_checks = around.checks;
  if (!around.found) {
    m.contact = line.contact;
    m.why = around.message;
    return m;
  }
  m.waypoints = around.waypoints;
  m.around = true;
  m.clearance = checker.padding();  // every segment of the path keeps at least the padding
  return m;
}

// A trajectory that holds `q` at `seconds`: a point to wait at, or to wait until.
JointTrajectory::Point hold(const std::vector<double>& q, double seconds) {
  JointTrajectory::Point p;
  p.positions = q;
  p.time_from_start = seconds;
  return p;
}

// The step's arms moved one after the other, each from where the ones before left it, its
// straight line or a path around; each waits for the ones before it and holds for the ones after.
std::optional<Refusal> move_in_turn(const MotionChecker& checker, const Arms& arms,
                                    const std::map<Arm, std::vector<double>>& current,
                                    const PlanSettings& settings, const JointValues& from,
                                    PlannedStep& planned) {
  JointValues state = from;
  double start = 0.0;
  std::vector<std::pair<double, double>> spans;  // each arm's [start, end) of the step, s
  for (PlannedArm& a : planned.arms) {
    const GroupInfo& group = arms.groups.at(a.arm);
    const ArmMotion m = move_arm(checker, group, state, a.ik.joints, a.intended);
    if (m.waypoints.empty()) {
      return Blocked{planned.index, arm_of(m.contact->link, a.arm), planned.phase, *m.contact,
                     m.why};
    }
    const double seconds =
        std::max(path_duration(group, current.at(a.arm), m.waypoints, settings.speed_fraction),
                 settings.min_step_duration / static_cast<double>(planned.arms.size()));
    a.trajectory = joint_path(group, current.at(a.arm), m.waypoints, seconds, settings.waypoints);
    a.clearance = m.clearance;
    a.planned_around = m.around;
    a.planning_seconds = m.planning_seconds;
    a.planning_checks = m.planning_checks;
    spans.emplace_back(start, start + seconds);
    start += seconds;
    set_joints(group, a.ik.joints, state);
  }
  planned.duration = std::max(planned.duration, start);
  for (std::size_t k = 0; k < planned.arms.size(); ++k) {
    JointTrajectory& t = planned.arms[k].trajectory;
    for (JointTrajectory::Point& p : t.points) p.time_from_start += spans[k].first;
    if (spans[k].first > 0.0)
      t.points.insert(t.points.begin(), hold(current.at(planned.arms[k].arm), spans[k].first));
    if (spans[k].second < planned.duration)
      t.points.push_back(hold(planned.arms[k].ik.joints, planned.duration));
  }
  return std::nullopt;
}

// Issue #60: the step's motions checked before anything moves. Free: each arm keeps its straight
// line, with the clearance. Touching: one arm's motion goes around what it would touch; with two
// arms, one moves after the other, each planned around with the other held. Else the step is
// refused with what the line would touch and where.
std::optional<Refusal> check_step(const MotionChecker& checker, const Arms& arms,
                                  const std::map<Arm, std::vector<double>>& current,
                                  const KinematicsInterface& kinematics,
                                  const PlanSettings& settings, PlannedStep& planned) {
  JointValues from, to;
  IntendedContact all;
  all.radius = settings.intended_contact_radius;
  for (PlannedArm& a : planned.arms) {
    const GroupInfo& group = arms.groups.at(a.arm);
    set_joints(group, current.at(a.arm), from);
    set_joints(group, a.ik.joints, to);
    Eigen::Isometry3d T_start = Eigen::Isometry3d::Identity();
    a.intended.radius = settings.intended_contact_radius;
    if (kinematics.forward(group.name, current.at(a.arm), T_start).ok())
      a.intended.near.push_back(T_start.translation());
    a.intended.near.push_back(a.T_base_ee.translation());
    all.near.insert(all.near.end(), a.intended.near.begin(), a.intended.near.end());
  }
  const MotionVerdict line = checker.check_line(from, to, all);
  for (PlannedArm& a : planned.arms) a.clearance = line.clearance;
  if (line.free()) return std::nullopt;
  // One arm after the other (with one arm, just it), in the program's order, else the other.
  std::optional<Refusal> first = move_in_turn(checker, arms, current, settings, from, planned);
  if (!first || planned.arms.size() < 2) return first;
  std::reverse(planned.arms.begin(), planned.arms.end());
  if (!move_in_turn(checker, arms, current, settings, from, planned)) return std::nullopt;
  std::reverse(planned.arms.begin(), planned.arms.end());
  return first;
}

// Issue #60: an IK solution that puts the arm inside something is no target: other solutions of
// the same pose are tried from random seeds (deterministic per step), the first that touches
// nothing kept. Without one the solution stays, and the motion's check refuses it, saying so.
void avoid_touching_targets(const MotionChecker& checker, const GroupInfo& group,
                            const KinematicsInterface& kinematics,
                            const std::map<Arm, std::vector<double>>& current, const Arms& arms,
                            std::size_t step, PlannedArm& a, double intended_radius) {
  const auto pose_of = [&](const std::vector<double>& q) {
    JointValues joints;
    for (const auto& [arm, values] : current) set_joints(arms.groups.at(arm), values, joints);
    set_joints(group, q, joints);
    return joints;
  };
  IntendedContact intended;
  intended.near = {a.T_base_ee.translation()};
  intended.radius = intended_radius;
  if (!checker.check_pose(pose_of(a.ik.joints), intended)) return;
  SplitMix64 rng(kTargetSeed + step);
  for (int k = 0; k < kTargetRetries; ++k) {
    const IkResult other = kinematics.inverse(group.name, a.T_base_ee, random_joints(group, rng));
    if (other.success && !checker.check_pose(pose_of(other.joints), intended)) {
      a.ik = other;
      return;
    }
  }
}

// One motion of the arms (a program step's targets, or its approach or retreat): IK for each arm's
// goal, seeded with its joints now, so that consecutive solutions stay on one branch; the joint
// lines, checked when there is a checker. Moves `current` to the goals, or returns why not.
std::optional<Refusal> solve_motion(const StepMotion& motion, std::size_t s,
                                    const std::optional<double>& step_duration,
                                    const KinematicsInterface& kinematics, const Arms& arms,
                                    const PlanSettings& settings, const MotionChecker* checker,
                                    std::map<Arm, std::vector<double>>& current,
                                    std::vector<PlannedStep>& steps) {
  PlannedStep planned;
  planned.index = s;
  planned.phase = motion.phase;
  double duration = step_duration.value_or(0.0);
  // Where the arms stand as this motion's goals are chosen: an arm already solved at its goal, so
  // that the other's is not chosen inside it (both hands on one chair).
  std::map<Arm, std::vector<double>> at_targets = current;
  for (const ArmGoal& goal : motion.goals) {
    PlannedArm a;
    a.arm = goal.arm;
    a.frame = goal.frame;
    a.gripper = goal.gripper;
    a.T_base_ee = goal.T_base_ee;
    a.ik = kinematics.inverse(arm_group(goal.arm), a.T_base_ee, current[goal.arm]);
    if (!a.ik.success) return Unreachable{s, goal.arm, motion.phase, a.ik.message};
    if (checker) {
      avoid_touching_targets(*checker, arms.groups.at(goal.arm), kinematics, at_targets, arms, s, a,
                             settings.intended_contact_radius);
    }
    at_targets[goal.arm] = a.ik.joints;
    duration = std::max(duration, motion_duration(arms.groups.at(goal.arm), current[goal.arm],
                                                  a.ik.joints, settings.speed_fraction));
    planned.arms.push_back(std::move(a));
  }
  planned.duration = std::max(duration, settings.min_step_duration);
  for (PlannedArm& a : planned.arms) {
    a.trajectory = joint_line(arms.groups.at(a.arm), current[a.arm], a.ik.joints, planned.duration,
                              settings.waypoints);
  }
  if (checker && !planned.arms.empty()) {
    if (std::optional<Refusal> blocked =
            check_step(*checker, arms, current, kinematics, settings, planned))
      return blocked;
  }
  for (PlannedArm& a : planned.arms) current[a.arm] = a.ik.joints;
  steps.push_back(std::move(planned));
  return std::nullopt;
}

// Steps 3-5 for one choice of instances: every program step's motions (approach.h) from
// `first_step` on, in order. Fills `steps`, or returns the first motion that cannot be carried out.
// An approach or retreat that cannot be made is left out, saying why in `skipped`: the motion to
// the target goes straight, checked as any other, as it did before approaches existed.
std::optional<Refusal> solve_steps(const Program& program, const Plan& plan,
                                   const KinematicsInterface& kinematics, const Arms& arms,
                                   const PlanSettings& settings, const MotionChecker* checker,
                                   std::vector<PlannedStep>& steps,
                                   std::vector<std::string>& skipped, std::size_t first_step = 0) {
  std::map<Arm, std::vector<double>> current = arms.start;
  const auto in_base = [&plan](const ArmTarget& target) {
    return target.relative_to_landmark()
               ? plan.landmark(target.frame)->T_base_landmark * target.T_frame_ee
               : target.T_frame_ee;
  };
  for (std::size_t s = first_step; s < program.steps.size(); ++s) {
    for (const StepMotion& motion : step_motions(program, s, settings.approach, in_base)) {
      // A step's own duration is the motion to its target's.
      const std::optional<double> duration =
          motion.phase == Phase::kTarget ? program.steps[s].duration : std::nullopt;
      std::optional<Refusal> failure =
          solve_motion(motion, s, duration, kinematics, arms, settings, checker, current, steps);
      if (failure && motion.phase == Phase::kTarget) return failure;
      if (failure) skipped.push_back(describe(*failure) + "; left out");
    }
  }
  return std::nullopt;
}

// Issue #60: where each arm's motion passes through space no camera has seen, from where it stood
// before the step (a trajectory's points begin after it), and one warning line per such motion:
// the plan acts on what it saw, and says where it could not look.
void warn_unseen(const MotionChecker& checker, const Arms& arms, Plan& plan) {
  std::map<Arm, std::vector<double>> current = arms.start;
  for (PlannedStep& step : plan.steps) {
    for (PlannedArm& a : step.arms) {
      const GroupInfo& group = arms.groups.at(a.arm);
      std::vector<JointValues> path(1);
      set_joints(group, current.at(a.arm), path.back());
      current[a.arm] = a.ik.joints;
      for (const JointTrajectory::Point& p : a.trajectory.points) {
        path.emplace_back();
        set_joints(group, p.positions, path.back());
      }
      a.unseen = checker.unseen_along(path);
      if (a.unseen.empty()) continue;
      plan.warnings.push_back(motion_name(step.index, step.phase, a.arm) +
                              ": passes through space no camera has seen, first near " +
                              format_point(a.unseen.front()) + " m in base_link (" +
                              std::to_string(a.unseen.size()) + " place" +
                              (a.unseen.size() == 1 ? "" : "s") + " 5 cm apart)");
    }
  }
}

void check_settings(const PlanSettings& s) {
  if (!(s.speed_fraction > 0.0 && s.speed_fraction <= 1.0))
    throw Error("plan: the speed fraction must be in (0, 1]");
  if (!(s.min_step_duration > 0.0)) throw Error("plan: the minimum step duration must be > 0");
  if (s.waypoints < 1) throw Error("plan: a trajectory needs at least one waypoint");
  if (!(s.height_tolerance >= 0.0)) throw Error("plan: the height tolerance must be >= 0");
  if (!(s.approach >= 0.0 && s.approach <= kMaxApproach)) {
    char text[64];
    std::snprintf(text, sizeof(text), "plan: the approach distance must be 0 to %g m",
                  kMaxApproach);
    throw Error(text);
  }
}

// Both arms' groups and their joints in `start`, also recorded as the plan's start.
Arms arms_at(const KinematicsInterface& kinematics, const JointState& start, Plan& plan) {
  std::map<std::string, double> positions;
  for (std::size_t i = 0; i < start.names.size() && i < start.positions.size(); ++i) {
    positions[start.names[i]] = start.positions[i];
  }
  Arms arms;
  for (Arm arm : {Arm::kLeft, Arm::kRight}) {
    const auto group = kinematics.group(arm_group(arm));
    if (!group) throw Error("plan: the robot has no group '" + arm_group(arm) + "'");
    arms.groups[arm] = *group;
    arms.start[arm] = group_start(*group, positions);
    for (std::size_t i = 0; i < group->joints.size(); ++i) {
      plan.start[group->joints[i].name] = arms.start[arm][i];
    }
  }
  return arms;
}

}  // namespace

std::vector<double> group_start(const GroupInfo& group,
                                const std::map<std::string, double>& positions) {
  std::vector<double> q;
  for (const JointInfo& j : group.joints) {
    const auto it = positions.find(j.name);
    if (it == positions.end()) {
      throw Error("plan: the robot's joint state lacks '" + j.name + "' of group '" + group.name +
                  "'");
    }
    q.push_back(it->second);
  }
  return q;
}

Plan replan_from(const Program& program, std::vector<LocatedLandmark> located,
                 const KinematicsInterface& kinematics, const JointState& start,
                 std::size_t first_step, const PlanSettings& settings) {
  validate_program(program);
  check_settings(settings);
  if (first_step > program.steps.size())
    throw Error("plan: step " + std::to_string(first_step) + " is past the program's end");
  Plan result;
  result.program = program.name;
  result.landmarks = std::move(located);
  const Arms arms = arms_at(kinematics, start, result);
  for (std::size_t s = first_step; s < program.steps.size(); ++s) {
    for (Arm arm : {Arm::kLeft, Arm::kRight}) {
      const std::optional<ArmTarget>& target = program.steps[s].arm(arm);
      if (target && target->relative_to_landmark() && !result.landmark(target->frame))
        throw Error("plan: step " + std::to_string(s) + " is relative to landmark '" +
                    target->frame + "', which was not located");
    }
  }
  std::vector<PlannedStep> steps;
  // No frame to check against here: the robot's own body only (an empty scene).
  const std::shared_ptr<const MotionChecker> checker =
      settings.motion_checker ? settings.motion_checker({}, start) : nullptr;
  std::vector<std::string> skipped;
  if (const std::optional<Refusal> failure = solve_steps(
          program, result, kinematics, arms, settings, checker.get(), steps, skipped, first_step)) {
    result.refusal = *failure;
  } else {
    result.steps = std::move(steps);
    result.warnings = std::move(skipped);
  }
  return result;
}

std::vector<std::string> capture_warnings(const Program& program,
                                          const std::map<std::string, Landmark>& landmarks) {
  std::vector<std::string> names;                      // in order of first use
  std::map<std::string, std::vector<std::size_t>> at;  // the steps relative to each
  for (std::size_t i = 0; i < program.steps.size(); ++i) {
    for (const Arm arm : {Arm::kLeft, Arm::kRight}) {
      const std::optional<ArmTarget>& target = program.steps[i].arm(arm);
      if (!target || !target->relative_to_landmark()) continue;
      std::vector<std::size_t>& steps = at[target->frame];
      if (steps.empty()) names.push_back(target->frame);
      if (steps.empty() || steps.back() != i) steps.push_back(i);
    }
  }
  std::vector<std::string> out;
  for (const std::string& name : names) {
    const auto l = landmarks.find(name);
    if (l == landmarks.end() || !l->second.findings.warned()) continue;
    std::string steps;
    for (const std::size_t i : at[name]) steps += (steps.empty() ? "" : ", ") + std::to_string(i);
    std::string line = "landmark '" + name + "' (step" + (at[name].size() == 1 ? " " : "s ") +
                       steps + ") was warned about at capture: ";
    const std::vector<std::string> warnings = l->second.findings.warnings();
    for (std::size_t k = 0; k < warnings.size(); ++k) line += (k ? "; " : "") + warnings[k];
    out.push_back(line);
  }
  return out;
}

Plan plan(const Program& program, const std::map<std::string, Landmark>& landmarks,
          const PointCloud& scene, const KinematicsInterface& kinematics, const JointState& start,
          const PlanSettings& settings, const std::vector<const PointCloud*>& motion_frames) {
  validate_program(program);
  check_settings(settings);
  Plan result;
  result.program = program.name;
  result.warnings = capture_warnings(program, landmarks);
  const Arms arms = arms_at(kinematics, start, result);

  // 1-2. Locate every landmark, or refuse.
  std::vector<Candidates> candidates;
  result.refusal = locate_landmarks(program, landmarks, scene, settings, candidates);
  if (result.refusal) return result;

  // 3-5. Everything before anything moves. When a step is out of reach relative to a landmark that
  // has other eligible instances, the next one in policy order is tried (a tool on a full rack:
  // take one the arm can reach); the refusal reported is the first, for the preferred instances.
  if (settings.progress)
    settings.progress("solving IK for " + std::to_string(program.steps.size()) + " steps");
  std::vector<std::size_t> choice(candidates.size(), 0);
  const auto locate = [&](const std::vector<std::size_t>& chosen) {
    result.landmarks.clear();
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      result.landmarks.push_back(choose(candidates[i], chosen[i]));
    }
  };
  if (settings.progress && settings.motion_checker)
    settings.progress("checking every motion against the scene and the robot");
  const std::vector<const PointCloud*> frames =
      motion_frames.empty() ? std::vector<const PointCloud*>{&scene} : motion_frames;
  const std::shared_ptr<const MotionChecker> checker =
      settings.motion_checker ? settings.motion_checker(frames, start) : nullptr;
  std::optional<Refusal> first_failure;
  while (true) {
    locate(choice);
    std::vector<PlannedStep> steps;
    std::vector<std::string> skipped;
    const std::optional<Refusal> failure =
        solve_steps(program, result, kinematics, arms, settings, checker.get(), steps, skipped);
    if (!failure) {
      result.steps = std::move(steps);
      result.warnings.insert(result.warnings.end(), skipped.begin(), skipped.end());
      if (checker) warn_unseen(*checker, arms, result);
      return result;
    }
    if (!first_failure) first_failure = failure;
    const auto [failed_step, failed_arm] = step_arm(*failure);
    const std::string& frame = program.steps[failed_step].arm(failed_arm)->frame;
    std::size_t i = 0;
    while (i < candidates.size() && candidates[i].entry->name != frame) ++i;
    if (!settings.try_other_instances || i == candidates.size() ||
        choice[i] + 1 >= candidates[i].matches.size()) {
      break;
    }
    ++choice[i];
  }
  Refusal refusal = *first_failure;
  const std::size_t tried = std::accumulate(choice.begin(), choice.end(), std::size_t{0});
  const std::string others = " (and with " + std::to_string(tried) + " other instance(s))";
  if (auto* u = std::get_if<Unreachable>(&refusal); u && tried > 0) u->reason += others;
  if (auto* b = std::get_if<Blocked>(&refusal); b && tried > 0) b->planner += others;
  result.refusal = refusal;
  locate(std::vector<std::size_t>(candidates.size(), 0));  // report the preferred instances
  return result;
}

}  // namespace lmk
