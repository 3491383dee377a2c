// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The paper's six PbD demonstration tasks (its Tables IV-IX) as data: each task's demonstration
// world, the landmark boxes a user draws in it, the arm poses the user demonstrates, and the test
// scenarios. demos/demo_tasks.cpp records and runs them; nothing here knows the answers the runs
// will give.

#include <optional>
#include <string>
#include <vector>

#include "lmk/demos/demo_world.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/symmetry.h"
#include "lmk/pbd/program.h"

namespace lmk::detail {

/// A landmark a user captures in the demonstration world: the box drawn around `part` of object
/// `object` (or `box`, base frame, when `object` is empty: a patch of free table).
struct DemoLandmark {
  std::string name;
  std::string object, part;
  Box box;
  /// When set, the box the user draws instead of the part's, in the object's frame.
  std::optional<Box> drawn;
  Symmetry symmetry;
  std::optional<InstancePolicy> select;
  bool flat = false;  ///< a free-surface patch (CaptureSettings::allow_flat)
};

/// The landmark a user captures around an object's part.
inline DemoLandmark part_landmark(std::string name, std::string object, std::string part,
                                  Symmetry symmetry = {}) {
  DemoLandmark l;
  l.name = std::move(name);
  l.object = std::move(object);
  l.part = std::move(part);
  l.symmetry = std::move(symmetry);
  return l;
}

/// One arm placed by the demonstrator: its tool pose in the demonstration world (base frame), the
/// frame the step should be relative to ("base" or a landmark), and the gripper.
struct DemoArmPose {
  std::string frame;
  Eigen::Isometry3d T_base_ee = Eigen::Isometry3d::Identity();
  GripperAction gripper = GripperAction::kOpen;
};

struct DemoStep {
  std::optional<DemoArmPose> left, right;
};

struct DemoProgram {
  std::string name;
  std::vector<std::string> landmarks;  ///< the task landmarks it declares
  std::vector<DemoStep> steps;
};

/// A person moving an object while the program runs (issue #48): once the arm's `after`-th
/// trajectory has been sent, object `object` stands at `to`, or is gone when `to` is unset.
struct DemoMove {
  std::string object;
  std::optional<Eigen::Isometry3d> to;
  std::size_t after = 1;
};

struct DemoScenario {
  std::string name;
  std::string program;
  bool should_act = true;
  std::string missing_landmark;  ///< when it should not act: the landmark it must say is missing
  /// Run in the world the previous scenario left, minus the object it picked (Task 3's second
  /// pick), instead of `world`.
  bool continues_previous = false;
  DemoWorld world;
  std::uint64_t seed = 0;  ///< sensor noise
  /// The landmark moved between two steps: watching notices it (DemoTasksSettings::watch).
  std::optional<DemoMove> move;
};

struct DemoTask {
  int number = 0;
  std::string title;
  double torso_height = 0.2;                               ///< m
  Eigen::Vector3d look_at = Eigen::Vector3d(0.7, 0, 0.7);  ///< where the head looks, base frame
  DemoWorld demonstration;
  std::vector<DemoLandmark> landmarks;
  std::vector<DemoProgram> programs;
  std::vector<DemoScenario> scenarios;

  const DemoLandmark& landmark(const std::string& name) const;
};

/// A task's header: its number and title, the torso height and where the head looks.
inline DemoTask new_task(int number, std::string title, double torso_height,
                         const Eigen::Vector3d& look_at) {
  DemoTask t;
  t.number = number;
  t.title = std::move(title);
  t.torso_height = torso_height;
  t.look_at = look_at;
  return t;
}

/// A scenario running `program`; it should act unless `missing` names the landmark it lacks.
inline DemoScenario new_scenario(std::string name, std::string program, std::string missing = "") {
  DemoScenario s;
  s.name = std::move(name);
  s.program = std::move(program);
  s.should_act = missing.empty();
  s.missing_landmark = std::move(missing);
  return s;
}

/// A step moving the right arm only.
inline DemoStep right_arm_step(std::string frame, const Eigen::Isometry3d& T_base_ee,
                               GripperAction gripper) {
  DemoStep s;
  s.right = DemoArmPose{std::move(frame), T_base_ee, gripper};
  return s;
}

// The six tasks, in the paper's order.
DemoTask hanging_tools_task();
DemoTask chair_task();
DemoTask bowls_on_shelf_task();
DemoTask bins_task();
DemoTask crowded_table_task();
DemoTask control_panel_task();
/// Task 7 (issue #60, not the paper's): the bins with things in the arm's way.
DemoTask obstacles_task();
/// Every task: the paper's six, then the obstacles.
std::vector<DemoTask> demo_task_definitions();

/// The bins of tasks 4 and 7 stand this far ahead of the robot, m.
inline constexpr double kBinX = 0.58;
/// The trash bin (square mouth; at (x, y, yaw), none when unset) and the recycling bin (round
/// mouth) on the floor.
void add_bins(DemoWorld& w, std::optional<Eigen::Vector3d> trash, Eigen::Vector3d recycling);
/// The bins' landmarks (their mouths) and programs ("drop in trash", "drop in recycling": hold an
/// item 20 cm over the mouth, let go, move up), demonstrated in `t.demonstration`.
void add_bin_programs(DemoTask& t);

// Poses shared by the definitions.
/// An object standing at (x, y, z) of the base frame with its front (-y in its own frame) turned
/// towards the robot (-x of the base), then turned by `yaw` about the vertical.
inline Eigen::Isometry3d facing_robot(double x, double y, double z, double yaw = 0.0) {
  return pose_from_xyz_rpy({x, y, z}, {0, 0, -0.5 * M_PI + yaw});
}
/// A tool at `p` pointing down (its x axis along -z), fingers closing along the base frame's
/// direction at `yaw` from +y.
inline Eigen::Isometry3d pointing_down(const Eigen::Vector3d& p, double yaw = 0.0) {
  return pose_from_xyz_rpy(p, {0, 0.5 * M_PI, yaw});
}

}  // namespace lmk::detail
