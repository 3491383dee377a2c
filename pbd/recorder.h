// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Recording a demonstration (paper, Section III-B; the original PR2 PbD): the person moves the
// arms, and each "save pose" appends a step. Each arm's pose is stored relative to the nearest
// landmark instance found in the demonstration scene, if one is within `max_distance`, and
// relative to the robot base otherwise.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/pbd/program.h"

namespace lmk {

/// A landmark instance found in the demonstration scene: its name in the program and its box in
/// the robot base frame (the match's box; T_base_landmark is box.pose).
struct LandmarkInstance {
  std::string name;
  Box box;
  /// What the landmark's capture check warned about (CaptureFindings::warnings(), as the match's
  /// confidence carries them, issue #59): a step recorded relative to this instance says so
  /// (Recorder::warnings()). Empty: nothing.
  std::vector<std::string> capture_warnings = {};
};

/// Distance from a point to a box: 0 inside, else to the nearest point of the box.
double distance_to_box(const Eigen::Vector3d& point, const Box& box);

struct RecorderSettings {
  /// A tool farther than this from every landmark instance (from its box) is recorded in the base
  /// frame. The original PR2 PbD attached a pose to an object within about 0.3 m.
  double max_distance = 0.3;
};

/// One arm at "save pose": its tool frame in the base frame (from the robot's FK) and its gripper.
struct ArmState {
  Eigen::Isometry3d T_base_ee = Eigen::Isometry3d::Identity();
  GripperAction gripper = GripperAction::kOpen;
};

class Recorder {
 public:
  /// Starts program `name` over `landmarks`, the landmarks its steps may refer to;
  /// `instances` are those found in the demonstration scene, in the base frame. Each landmark's
  /// demonstrated pose, unless given, is the box of the first instance a step is anchored on (in
  /// step order), else of its first instance in the scene. Throws lmk::Error
  /// for an instance whose landmark is not among `landmarks`, or a bad box.
  Recorder(std::string name, std::vector<ProgramLandmark> landmarks,
           std::vector<LandmarkInstance> instances, const RecorderSettings& settings = {});

  /// Appends a step moving the given arms (at least one); returns its index.
  std::size_t save_pose(const std::optional<ArmState>& left, const std::optional<ArmState>& right,
                        std::optional<double> duration = std::nullopt);

  /// Re-expresses one arm of a recorded step in `frame` ("base" or a landmark with an instance in
  /// the demonstration scene: the one nearest to the tool), keeping its pose in the base frame.
  /// Throws lmk::Error for a bad step or arm, or a landmark without an instance.
  void set_frame(std::size_t step, Arm arm, const std::string& frame);

  /// One line per arm of a recorded step that is relative to an instance whose capture check warned
  /// (LandmarkInstance::capture_warnings): "step 2, right arm: relative to 'rack', which was
  /// warned about at capture: ...". What a person recording should hear before relying on it.
  std::vector<std::string> warnings() const;

  /// The recorded pose of an arm in the base frame.
  Eigen::Isometry3d base_pose(std::size_t step, Arm arm) const;

  const Program& program() const { return program_; }
  const std::vector<LandmarkInstance>& instances() const { return instances_; }

 private:
  static constexpr int kBase = -1;
  /// The instance nearest to `point` (of landmark `name` if given) if it is within
  /// `max_distance`, else kBase.
  int nearest(const Eigen::Vector3d& point, const std::string* name, double max_distance) const;
  ArmTarget target_in(int anchor, const Eigen::Isometry3d& T_base_ee, GripperAction g) const;
  /// Sets every landmark's demonstrated pose from the anchors (see the constructor).
  void refresh_demonstrations();

  Program program_;
  std::vector<LandmarkInstance> instances_;
  RecorderSettings settings_;
  /// Per step and arm (left, right): the index of the instance the target is relative to, or
  /// kBase.
  std::vector<std::array<int, 2>> anchors_;
  /// The demonstrated poses the caller gave with the landmarks, which win over the anchors.
  std::vector<std::optional<Eigen::Isometry3d>> declared_demonstrations_;
};

}  // namespace lmk
