// SPDX-License-Identifier: BSD-3-Clause
// Program endpoints: the PbD programs of --programs, and their plans on a scene for a simulated
// PR2 at rest (pbd/plan.h): landmarks located, every step's gripper pose in the base frame, and
// the refusal exactly as the robot would give it.
#include <cstdio>

#include "lmk/geometry/error.h"
#include "lmk/json/pose_json.h"
#include "lmk/pbd/internal/plan_json.h"
#include "lmk/pbd/plan.h"
#include "lmk/pr2/pr2_motion_check.h"
#include "lmk/pr2/pr2_robots.h"
#include "lmk/pr2/simulated_pr2.h"
#include "lmk/serve/api.h"
#include "lmk/serve/api_error.h"
#include "lmk/serve/request_fields.h"
#include "lmk/serve/static_files.h"

namespace lmk::serve {
namespace {

namespace fs = std::filesystem;

// Every step's targets where they can be drawn: in the base frame directly, or relative to a
// landmark the plan located. A target relative to a landmark not found has no pose.
nlohmann::json targets_json(const Program& program, const Plan& plan) {
  nlohmann::json targets = nlohmann::json::array();
  for (std::size_t i = 0; i < program.steps.size(); ++i) {
    for (Arm arm : {Arm::kLeft, Arm::kRight}) {
      const auto& target = program.steps[i].arm(arm);
      if (!target) continue;
      nlohmann::json t = {{"step", i},
                          {"arm", arm_name(arm)},
                          {"frame", target->frame},
                          {"gripper", gripper_action_name(target->gripper)}};
      std::optional<Eigen::Isometry3d> T_base_ee;
      if (!target->relative_to_landmark()) {
        T_base_ee = target->T_frame_ee;
      } else if (const LocatedLandmark* l = plan.landmark(target->frame)) {
        T_base_ee = l->T_base_landmark * target->T_frame_ee;
      }
      t["pose"] = T_base_ee ? detail::pose_to_json(*T_base_ee) : nlohmann::json(nullptr);
      targets.push_back(t);
    }
  }
  return targets;
}

// Issue #60: where each arm's tool frame goes along its planned motion, base frame, from where it
// stood before the step: the swept path the page draws.
nlohmann::json tool_paths_json(const Plan& plan, const KinematicsInterface& kinematics) {
  std::map<Arm, std::vector<double>> at;  // each arm's joints before the step
  for (const Arm arm : {Arm::kLeft, Arm::kRight}) {
    if (const std::optional<GroupInfo> group = kinematics.group(arm_group(arm)))
      at[arm] = group_start(*group, plan.start);
  }
  const auto add_tool = [&](Arm arm, const std::vector<double>& q, nlohmann::json& points) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    if (kinematics.forward(arm_group(arm), q, T).ok())
      points.push_back(detail::vector_to_json(T.translation()));
  };
  nlohmann::json paths = nlohmann::json::array();
  for (const PlannedStep& step : plan.steps) {
    for (const PlannedArm& a : step.arms) {
      nlohmann::json points = nlohmann::json::array();
      add_tool(a.arm, at[a.arm], points);
      for (const JointTrajectory::Point& p : a.trajectory.points)
        add_tool(a.arm, p.positions, points);
      paths.push_back({{"step", step.index},
                       {"phase", phase_name(step.phase)},
                       {"arm", arm_name(a.arm)},
                       {"planned_around", a.planned_around},
                       {"points", points}});
      at[a.arm] = a.ik.joints;
    }
  }
  return paths;
}

}  // namespace

fs::path Api::program_path(const std::string& name) const {
  if (programs_dir_.empty()) throw not_found("no programs: start lmk serve with --programs DIR");
  const fs::path path = programs_dir_ / (checked_name(name, "program") + ".json");
  if (!fs::is_regular_file(path))
    throw not_found("no program '" + printable(name, kEchoedBytes) + "'");
  return path;
}

ApiResponse Api::programs() const {
  nlohmann::json list = nlohmann::json::array();
  if (!programs_dir_.empty()) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(programs_dir_)) {
      if (e.is_regular_file() && e.path().extension() == ".json") files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
      nlohmann::json j = {{"name", f.stem().string()}};
      try {
        const Program p = load_program(f.string());
        j["program"] = p.name;
        j["steps"] = p.steps.size();
        nlohmann::json names = nlohmann::json::array();
        for (const ProgramLandmark& l : p.landmarks) names.push_back(l.name);
        j["landmarks"] = names;
      } catch (const Error& e) {
        j["error"] = e.what();  // other JSON files, or damaged programs: listed with the reason
      }
      list.push_back(j);
    }
  }
  return {200, {{"programs", list}}};
}

ApiResponse Api::program(const std::string& name) const {
  const fs::path path = program_path(name);
  const Program p = load_program(path.string());
  return {200, {{"name", name}, {"program", nlohmann::json::parse(program_to_json(p))}}};
}

ApiResponse Api::plan(const std::string& name, const std::string& body_text) {
  const nlohmann::json body = parse_body(body_text, "plan");
  const fs::path path = program_path(name);
  const Scene scene = scenes_.get(required_string(body, "scene", "plan"));
  const double torso = optional_number(body, "torso", settings_.torso, "plan");
  // Issue #60: every motion checked against the scene and the robot, as lmk pbd plan
  // --check-collisions does; the padding as its --padding.
  const bool collisions = optional_bool(body, "collisions", true, "plan");
  Pr2MotionCheckSettings check;
  check.motion.padding = optional_number(body, "padding", check.motion.padding, "plan");
  if (!(check.motion.padding >= kMinPadding && check.motion.padding <= kMaxPadding)) {
    char why[96];
    std::snprintf(why, sizeof(why), "plan: padding %g m: must be %g to %g", check.motion.padding,
                  kMinPadding, kMaxPadding);
    throw bad_request(why);
  }
  const Program program = load_program(path.string());
  // A program names its landmark files; they must stay within the directories lmk serve was given.
  for (const ProgramLandmark& l : program.landmarks) {
    const fs::path file =
        fs::path(l.file).is_absolute() ? fs::path(l.file) : programs_dir_ / l.file;
    if (!lies_within(file, programs_dir_) && !lies_within(file, library_.directory())) {
      throw forbidden("plan: program '" + name + "': landmark '" + l.name + "' file " + l.file +
                      " lies outside --programs and --landmarks");
    }
  }
  const auto landmarks = std::make_shared<const std::map<std::string, Landmark>>(
      load_program_landmarks(program, programs_dir_.string()));
  PlanSettings plan_settings;
  plan_settings.find = scene_find_settings();
  apply_find_settings(body, "plan", plan_settings.find);

  // The plan searches the scene for each landmark in turn: one search's peak.
  MemoryBudget::Reservation memory = reserve_search(scene, plan_settings.find.scene, "plan");
  return run_job("plan", body, std::move(memory), [=](JobProgress& progress) mutable {
    SimulatedPr2 robot = start_simulated_pr2(torso);
    JointState start;
    robot.read_joint_state(start);
    if (collisions) plan_settings.motion_checker = pr2_motion_checker(robot.kinematics(), check);
    double done = 0.0;
    const double steps = static_cast<double>(program.landmarks.size() + 1);
    plan_settings.find.execution.stop = progress.stop_check();
    plan_settings.progress = [&](const std::string& line) {
      progress.report(std::min(done++ / steps, 0.99), line);
    };
    const Plan p =
        lmk::plan(program, *landmarks, *scene.cloud, robot.kinematics(), start, plan_settings);
    progress.report(1.0, "done");
    return nlohmann::json{{"name", name},
                          {"scene", scene.id},
                          {"plan", detail::plan_to_json(p)},
                          {"targets", targets_json(program, p)},
                          {"paths", tool_paths_json(p, robot.kinematics())}};
  });
}

}  // namespace lmk::serve
