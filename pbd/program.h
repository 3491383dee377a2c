// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A PbD program (paper, Section III-B): a named sequence of steps, each a target end-effector pose
// per arm, in the robot base frame or relative to a named landmark, with a gripper state. The
// landmarks are referenced by name and by their .lmk file; programs are stored as versioned JSON
// (docs/programs.md).

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/symmetry.h"

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
  /// Whether either arm's target is relative to a landmark.
  bool relative_to_landmark() const {
    return (left && left->relative_to_landmark()) || (right && right->relative_to_landmark());
  }
};

/// Which instance a step goes to when a landmark is found more than once in the scene.
enum class InstancePolicy {
  kBestError,  ///< the match with the lowest error (the paper's "best match")
  /// The instance nearest to where the landmark was in the demonstration.
  kNearestToDemonstration,
  /// Only instances at the demonstrated height (within the planner's tolerance), best error first:
  /// for a landmark that could also match elsewhere, such as an empty table patch that the top of
  /// a large flat box also offers (the paper's Task 5 failure).
  kDemonstratedHeight,
};
/// "best-error", "nearest-to-demonstration", "demonstrated-height".
const char* instance_policy_name(InstancePolicy policy);
/// The policy called `name`; throws lmk::Error naming the known ones.
InstancePolicy instance_policy_from_name(const std::string& name);

struct ProgramLandmark {
  ProgramLandmark() = default;
  ProgramLandmark(std::string name_in, std::string file_in)
      : name(std::move(name_in)), file(std::move(file_in)) {}

  std::string name;
  std::string file;  ///< .lmk; relative paths are relative to the program file
  /// Where the landmark was in the demonstration, T_base_landmark (the box of the instance the
  /// steps were recorded against). The recorder fills it; the policies that compare with the
  /// demonstration and symmetric landmarks need it.
  std::optional<Eigen::Isometry3d> demonstration;
  /// A symmetric landmark's pose is found only up to its symmetry; the planner turns it to the
  /// equivalent pose nearest the demonstrated orientation, so that a bowl's rim is grasped on the
  /// side the demonstration grasped it.
  Symmetry symmetry;
  /// Overrides the planner's default policy for this landmark.
  std::optional<InstancePolicy> select;
};

/// What a watching execution (pbd/watch.h) does when a landmark the remaining steps are relative
/// to has moved since planning.
enum class WhenMoved {
  kReplan,  ///< plan the remaining steps again from the new pose
  kStop,    ///< stop the program, saying which landmark moved
};
/// "re-plan" or "stop".
const char* when_moved_name(WhenMoved when);
/// Throws lmk::Error naming the known names.
WhenMoved when_moved_from_name(const std::string& name);

struct Program {
  std::string name;
  std::vector<ProgramLandmark> landmarks;
  std::vector<ProgramStep> steps;
  /// What to do when a landmark moves while the program runs watching (issue #48); unset: the
  /// execution's WatchSettings (re-plan by default). A program that must not adapt (a tool
  /// hung in one exact place) says stop.
  std::optional<WhenMoved> when_landmark_moves;

  const ProgramLandmark* landmark(const std::string& name) const;
};

/// The names of the landmarks the steps from `first_step` on are relative to, in the order the
/// program declares them: what a plan must locate, and what a watching run must keep an eye on.
std::vector<std::string> landmarks_used(const Program& program, std::size_t first_step = 0);

/// Checks what a program must satisfy whatever its source: a name; unique, non-empty landmark
/// names, none called "base"; a demonstrated pose where a symmetry or a policy that compares with
/// the demonstration needs one; symmetry axes non-zero and orders 0 or at least 2; every step moves
/// at least one arm; every target's frame is "base" or a declared landmark; poses finite and
/// proper; durations positive. Throws lmk::Error naming the offending step and arm ("program 'x':
/// steps[2].left: unknown landmark 'rack'").
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
