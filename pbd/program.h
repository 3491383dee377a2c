#pragma once
// A PbD program (paper, Section III-B): a named sequence of steps, each a target end-effector pose
// per arm, in the robot base frame or relative to a named landmark, with a gripper state. The
// landmarks are referenced by name and by their .lmk file; programs are stored as versioned JSON
// (docs/programs.md).

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace lmk {

inline constexpr int kProgramFormatVersion = 1;
/// The frame name of targets expressed in the robot base frame.
inline constexpr const char* kBaseFrame = "base";

enum class Arm { kLeft, kRight };
/// "left" or "right".
const char* arm_name(Arm arm);
/// The PR2 group of an arm: "left_arm" or "right_arm"; its gripper: "left_gripper"...
std::string arm_group(Arm arm);
std::string arm_gripper(Arm arm);

enum class GripperAction { kOpen, kClose };
const char* gripper_action_name(GripperAction action);  ///< "open" or "close"

/// One arm's part of a step: where its tool frame goes, T_frame_ee, and then its gripper.
struct ArmTarget {
  /// kBaseFrame, or the name of one of the program's landmarks.
  std::string frame = kBaseFrame;
  Eigen::Isometry3d T_frame_ee = Eigen::Isometry3d::Identity();
  GripperAction gripper = GripperAction::kOpen;
  bool relative_to_landmark() const { return frame != kBaseFrame; }
};

struct ProgramStep {
  std::optional<ArmTarget> left, right;
  /// Seconds the motion to this step takes; unset, the planner picks one from the joint speeds.
  std::optional<double> duration;

  const std::optional<ArmTarget>& arm(Arm a) const { return a == Arm::kLeft ? left : right; }
  std::optional<ArmTarget>& arm(Arm a) { return a == Arm::kLeft ? left : right; }
};

struct ProgramLandmark {
  std::string name;
  std::string file;  ///< .lmk; relative paths are relative to the program file
};

struct Program {
  std::string name;
  std::vector<ProgramLandmark> landmarks;
  std::vector<ProgramStep> steps;

  const ProgramLandmark* landmark(const std::string& name) const;
};

/// Checks what a program must satisfy whatever its source: a name; unique, non-empty landmark
/// names, none called "base"; every step moves at least one arm; every target's frame is "base" or
/// a declared landmark; poses finite and proper; durations positive. Throws lmk::Error naming the
/// offending step and arm ("program 'x': steps[2].left: unknown landmark 'rack'").
void validate_program(const Program& program);

/// Reads and validates a program file: the JSON schema, the version (kProgramFormatVersion),
/// unit quaternions, and validate_program. Throws lmk::Error with the file and field.
Program load_program(const std::string& path);

/// Validates, then writes the program atomically (a crash leaves the old file or the new one).
void save_program(const std::string& path, const Program& program);

/// The program as the JSON text save_program writes.
std::string program_to_json(const Program& program);

/// Parses program JSON text; `source` names it in messages.
Program program_from_json(const std::string& text, const std::string& source);

}  // namespace lmk
