// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pbd/program.h"

#include <cmath>
#include <set>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"

namespace lmk {

const char* arm_name(Arm arm) { return arm == Arm::kLeft ? "left" : "right"; }
std::string arm_group(Arm arm) { return std::string(arm_name(arm)) + "_arm"; }
std::string arm_gripper(Arm arm) { return arm_name(arm); }

const char* gripper_action_name(GripperAction action) {
  return action == GripperAction::kOpen ? "open" : "close";
}

const char* instance_policy_name(InstancePolicy policy) {
  switch (policy) {
    case InstancePolicy::kBestError:
      return "best-error";
    case InstancePolicy::kNearestToDemonstration:
      return "nearest-to-demonstration";
    case InstancePolicy::kDemonstratedHeight:
      return "demonstrated-height";
  }
  return "?";
}

InstancePolicy instance_policy_from_name(const std::string& name) {
  for (InstancePolicy p : {InstancePolicy::kBestError, InstancePolicy::kNearestToDemonstration,
                           InstancePolicy::kDemonstratedHeight}) {
    if (name == instance_policy_name(p)) return p;
  }
  throw Error("unknown instance policy '" + name +
              "' (best-error, nearest-to-demonstration, demonstrated-height)");
}

const char* when_moved_name(WhenMoved when) {
  return when == WhenMoved::kStop ? "stop" : "re-plan";
}

WhenMoved when_moved_from_name(const std::string& name) {
  for (WhenMoved w : {WhenMoved::kReplan, WhenMoved::kStop}) {
    if (name == when_moved_name(w)) return w;
  }
  throw Error("unknown answer to a moved landmark '" + name + "' (re-plan, stop)");
}

std::vector<std::string> landmarks_used(const Program& program, std::size_t first_step) {
  std::set<std::string> used;
  for (std::size_t s = first_step; s < program.steps.size(); ++s) {
    for (Arm arm : {Arm::kLeft, Arm::kRight}) {
      const std::optional<ArmTarget>& target = program.steps[s].arm(arm);
      if (target && target->relative_to_landmark()) used.insert(target->frame);
    }
  }
  std::vector<std::string> names;
  for (const ProgramLandmark& l : program.landmarks) {
    if (used.count(l.name)) names.push_back(l.name);
  }
  return names;
}

const ProgramLandmark* Program::landmark(const std::string& name) const {
  for (const ProgramLandmark& l : landmarks) {
    if (l.name == name) return &l;
  }
  return nullptr;
}

void validate_program(const Program& program) {
  const std::string who = "program '" + program.name + "': ";
  if (program.name.empty()) throw Error("program: the name is empty");
  std::set<std::string> names;
  for (std::size_t i = 0; i < program.landmarks.size(); ++i) {
    const ProgramLandmark& l = program.landmarks[i];
    const std::string where = who + "landmarks[" + std::to_string(i) + "]: ";
    if (l.name.empty()) throw Error(where + "the name is empty");
    if (l.name == kBaseFrame) throw Error(where + "'base' names the robot base frame");
    if (l.file.empty()) throw Error(where + "landmark '" + l.name + "' has no .lmk file");
    if (!names.insert(l.name).second) throw Error(where + "landmark '" + l.name + "' twice");
    if (l.demonstration && !is_valid_pose(*l.demonstration, 1e-4)) {
      throw Error(where + "the demonstrated pose is not a finite rigid transform");
    }
    if (l.symmetry.axis) {
      if (!l.symmetry.axis->allFinite() || l.symmetry.axis->norm() < 1e-9) {
        throw Error(where + "the symmetry axis must be a finite, non-zero vector");
      }
      if (l.symmetry.order == 1 || l.symmetry.order < 0) {
        throw Error(where + "the symmetry order must be 0 (revolution) or at least 2");
      }
    }
    const bool needs_demonstration =
        l.symmetry.axis || (l.select && *l.select != InstancePolicy::kBestError);
    if (needs_demonstration && !l.demonstration) {
      throw Error(where + "landmark '" + l.name +
                  "' needs its demonstrated pose for its symmetry or its policy");
    }
  }
  for (std::size_t i = 0; i < program.steps.size(); ++i) {
    const ProgramStep& step = program.steps[i];
    const std::string where = who + "steps[" + std::to_string(i) + "]";
    if (!step.left && !step.right) throw Error(where + ": moves neither arm");
    if (step.duration && !(*step.duration > 0.0 && std::isfinite(*step.duration))) {
      throw Error(where + ": the duration must be positive seconds");
    }
    for (Arm arm : {Arm::kLeft, Arm::kRight}) {
      const std::optional<ArmTarget>& target = step.arm(arm);
      if (!target) continue;
      const std::string at = where + "." + arm_name(arm) + ": ";
      if (target->frame.empty()) throw Error(at + "the frame is empty");
      if (target->relative_to_landmark() && !program.landmark(target->frame)) {
        throw Error(at + "unknown landmark '" + target->frame + "'");
      }
      if (!is_valid_pose(target->T_frame_ee, 1e-4)) {
        throw Error(at + "the pose is not a finite rigid transform");
      }
    }
  }
}

}  // namespace lmk
