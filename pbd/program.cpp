#include "pbd/program.h"

#include <cmath>
#include <set>

#include "geometry/error.h"
#include "geometry/pose.h"

namespace lmk {

const char* arm_name(Arm arm) { return arm == Arm::kLeft ? "left" : "right"; }
std::string arm_group(Arm arm) { return std::string(arm_name(arm)) + "_arm"; }
std::string arm_gripper(Arm arm) { return std::string(arm_name(arm)) + "_gripper"; }

const char* gripper_action_name(GripperAction action) {
  return action == GripperAction::kOpen ? "open" : "close";
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
