// SPDX-License-Identifier: BSD-3-Clause
// Program files: {"format": "lmk-program", "version": 1, "name": ..., "landmarks": [...],
// "steps": [...]} (docs/programs.md).

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/input_file.h"
#include "lmk/json/json_reader.h"
#include "lmk/pbd/program.h"

namespace lmk {

namespace {

using nlohmann::json;
constexpr const char* kFormat = "lmk-program";

json arm_to_json(const ArmTarget& t) {
  json j = detail::pose_to_json(t.T_frame_ee);
  j["frame"] = t.frame;
  j["gripper"] = gripper_action_name(t.gripper);
  return j;
}

ArmTarget arm_from_json(const json& j, const std::string& where, const detail::JsonReader& r) {
  if (!j.is_object()) r.fail(where, "must be an object with frame, position, quaternion, gripper");
  ArmTarget t;
  t.frame = r.text(j, where, "frame");
  t.T_frame_ee = r.pose(j, where);
  const std::string gripper = r.text(j, where, "gripper");
  if (gripper == "open") {
    t.gripper = GripperAction::kOpen;
  } else if (gripper == "close") {
    t.gripper = GripperAction::kClose;
  } else {
    r.fail(where + ".gripper", "must be \"open\" or \"close\", not \"" + gripper + "\"");
  }
  return t;
}

json landmark_to_json(const ProgramLandmark& l) {
  json j = {{"name", l.name}, {"file", l.file}};
  if (l.demonstration) j["demonstration"] = detail::pose_to_json(*l.demonstration);
  if (l.symmetry.axis) {
    const Eigen::Vector3d& a = *l.symmetry.axis;
    j["symmetry"] = {{"axis", {a.x(), a.y(), a.z()}}, {"order", l.symmetry.order}};
  }
  if (l.select) j["select"] = instance_policy_name(*l.select);
  return j;
}

bool has(const json& j, const char* key) { return j.contains(key) && !j[key].is_null(); }

ProgramLandmark landmark_from_json(const json& j, const std::string& where,
                                   const detail::JsonReader& r) {
  if (!j.is_object()) r.fail(where, "must be an object with name and file");
  ProgramLandmark l;
  l.name = r.text(j, where, "name");
  l.file = r.text(j, where, "file");
  if (has(j, "demonstration"))
    l.demonstration = r.pose(j["demonstration"], where + ".demonstration");
  if (has(j, "symmetry")) {
    const json& s = j["symmetry"];
    const std::string at = where + ".symmetry";
    if (!s.is_object()) r.fail(at, "must be an object with axis and order");
    l.symmetry.axis = r.numbers(r.field(s, at, "axis"), at + ".axis", 3);
    if (has(s, "order")) {
      if (!s["order"].is_number_integer()) r.fail(at + ".order", "must be an integer");
      l.symmetry.order = s["order"].get<int>();
    }
  }
  if (has(j, "select")) {
    try {
      l.select = instance_policy_from_name(r.text(j, where, "select"));
    } catch (const Error& e) {
      r.fail(where + ".select", e.what());
    }
  }
  return l;
}

Program parse(const json& j, const detail::JsonReader& r) {
  if (!j.is_object()) r.fail("", "must hold a JSON object");
  if (j.contains("format") && j["format"] != kFormat) {
    r.fail("format", "is " + j["format"].dump() + ", not \"" + kFormat + "\"");
  }
  r.require_version(j, kProgramFormatVersion, "program");
  Program p;
  p.name = r.text(j, "", "name");
  const json& landmarks = r.field(j, "", "landmarks");
  if (!landmarks.is_array()) r.fail("landmarks", "must be an array");
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    const std::string where = detail::at("", "landmarks", i);
    p.landmarks.push_back(landmark_from_json(landmarks[i], where, r));
  }
  const json& steps = r.field(j, "", "steps");
  if (!steps.is_array()) r.fail("steps", "must be an array");
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const std::string where = detail::at("", "steps", i);
    const json& s = steps[i];
    if (!s.is_object()) r.fail(where, "must be an object");
    ProgramStep step;
    for (Arm arm : {Arm::kLeft, Arm::kRight}) {
      const char* name = arm_name(arm);
      if (has(s, name)) {
        step.arm(arm) = arm_from_json(s[name], where + "." + name, r);
      }
    }
    if (!step.left && !step.right)
      r.fail(where, "moves neither arm: give \"left\", \"right\" or both");
    if (has(s, "duration")) {
      if (!s["duration"].is_number() || !(s["duration"].get<double>() > 0.0)) {
        r.fail(where + ".duration", "must be a positive number of seconds");
      }
      step.duration = s["duration"].get<double>();
    }
    p.steps.push_back(std::move(step));
  }
  if (has(j, "when_landmark_moves")) {
    try {
      p.when_landmark_moves = when_moved_from_name(r.text(j, "", "when_landmark_moves"));
    } catch (const Error& e) {
      r.fail("when_landmark_moves", e.what());
    }
  }
  return p;
}

}  // namespace

std::string program_to_json(const Program& program) {
  json landmarks = json::array(), steps = json::array();
  for (const ProgramLandmark& l : program.landmarks) {
    landmarks.push_back(landmark_to_json(l));
  }
  for (const ProgramStep& step : program.steps) {
    json s = json::object();
    for (Arm arm : {Arm::kLeft, Arm::kRight}) {
      if (step.arm(arm)) s[arm_name(arm)] = arm_to_json(*step.arm(arm));
    }
    if (step.duration) s["duration"] = *step.duration;
    steps.push_back(std::move(s));
  }
  json j = {{"format", kFormat},
            {"version", kProgramFormatVersion},
            {"name", program.name},
            {"landmarks", std::move(landmarks)},
            {"steps", std::move(steps)}};
  if (program.when_landmark_moves)
    j["when_landmark_moves"] = when_moved_name(*program.when_landmark_moves);
  return j.dump(2) + "\n";
}

Program program_from_json(const std::string& text, const std::string& source) {
  const detail::JsonReader r(source);
  const json j = r.parse(text);
  Program p = parse(j, r);
  try {
    validate_program(p);
  } catch (const Error& e) {
    r.fail("", e.what());
  }
  return p;
}

Program load_program(const std::string& path) {
  return program_from_json(read_input_file(path, kProgramInput), path);
}

void save_program(const std::string& path, const Program& program) {
  validate_program(program);
  write_text_atomically(path, program_to_json(program));
}

}  // namespace lmk
