// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pbd/recorder.h"

#include <cmath>
#include <limits>

#include "lmk/geometry/error.h"

namespace lmk {

double distance_to_box(const Eigen::Vector3d& point, const Box& box) {
  const Eigen::Vector3d local = box.pose.inverse() * point;
  const Eigen::Vector3d half = 0.5 * box.size;
  return (local - local.cwiseMax(-half).cwiseMin(half)).norm();
}

Recorder::Recorder(std::string name, std::vector<ProgramLandmark> landmarks,
                   std::vector<LandmarkInstance> instances, const RecorderSettings& settings)
    : instances_(std::move(instances)), settings_(settings) {
  program_.name = std::move(name);
  program_.landmarks = std::move(landmarks);
  if (!(settings_.max_distance >= 0.0)) throw Error("recorder: the distance must not be negative");
  for (const LandmarkInstance& instance : instances_) {
    if (!program_.landmark(instance.name)) {
      throw Error("recorder: an instance of '" + instance.name +
                  "', which the program does not declare");
    }
    if (!instance.box.is_valid())
      throw Error("recorder: instance of '" + instance.name + "': bad box");
  }
  declared_demonstrations_.reserve(program_.landmarks.size());
  for (const ProgramLandmark& l : program_.landmarks) {
    declared_demonstrations_.push_back(l.demonstration);
  }
  refresh_demonstrations();
  // After the demonstrated poses are known: a symmetric landmark needs one.
  validate_program(program_);
}

void Recorder::refresh_demonstrations() {
  for (std::size_t k = 0; k < program_.landmarks.size(); ++k) {
    ProgramLandmark& landmark = program_.landmarks[k];
    landmark.demonstration = declared_demonstrations_[k];
    if (landmark.demonstration) continue;
    // The first instance a step is anchored on, in step order; else the landmark's first instance
    // in the scene, so that a landmark no step uses yet still knows where it was.
    std::optional<std::size_t> chosen;
    for (const auto& anchors : anchors_) {
      for (const int a : anchors) {
        if (!chosen && a != kBase && instances_[static_cast<std::size_t>(a)].name == landmark.name)
          chosen = static_cast<std::size_t>(a);
      }
    }
    for (std::size_t i = 0; i < instances_.size() && !chosen; ++i) {
      if (instances_[i].name == landmark.name) chosen = i;
    }
    if (chosen) landmark.demonstration = instances_[*chosen].box.pose;
  }
}

int Recorder::nearest(const Eigen::Vector3d& point, const std::string* name,
                      double max_distance) const {
  int best = kBase;
  // Strictly nearer wins, so ties go to the first instance; a distance of exactly max_distance
  // still counts as within.
  double best_distance = std::nextafter(max_distance, std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < instances_.size(); ++i) {
    if (name && instances_[i].name != *name) continue;
    const double d = distance_to_box(point, instances_[i].box);
    if (d < best_distance) {
      best_distance = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

ArmTarget Recorder::target_in(int anchor, const Eigen::Isometry3d& T_base_ee,
                              GripperAction gripper) const {
  ArmTarget t;
  t.gripper = gripper;
  if (anchor == kBase) {
    t.frame = kBaseFrame;
    t.T_frame_ee = T_base_ee;
  } else {
    const LandmarkInstance& instance = instances_[static_cast<std::size_t>(anchor)];
    t.frame = instance.name;
    // T_landmark_ee = T_base_landmark^-1 T_base_ee, so that T_base_landmark' T_landmark_ee
    // puts the tool in the same place on a landmark found elsewhere.
    t.T_frame_ee = instance.box.pose.inverse() * T_base_ee;
  }
  return t;
}

std::size_t Recorder::save_pose(const std::optional<ArmState>& left,
                                const std::optional<ArmState>& right,
                                std::optional<double> duration) {
  if (!left && !right) throw Error("recorder: save pose needs at least one arm");
  ProgramStep step;
  step.duration = duration;
  std::array<int, 2> anchors = {kBase, kBase};
  for (Arm arm : {Arm::kLeft, Arm::kRight}) {
    const std::optional<ArmState>& state = arm == Arm::kLeft ? left : right;
    if (!state) continue;
    const int anchor = nearest(state->T_base_ee.translation(), nullptr, settings_.max_distance);
    anchors[arm == Arm::kLeft ? 0 : 1] = anchor;
    step.arm(arm) = target_in(anchor, state->T_base_ee, state->gripper);
  }
  program_.steps.push_back(step);
  try {
    validate_program(program_);
  } catch (...) {
    program_.steps.pop_back();
    throw;
  }
  anchors_.push_back(anchors);
  refresh_demonstrations();
  return program_.steps.size() - 1;
}

Eigen::Isometry3d Recorder::base_pose(std::size_t step, Arm arm) const {
  if (step >= program_.steps.size()) {
    throw Error("recorder: no step " + std::to_string(step) + " (the program has " +
                std::to_string(program_.steps.size()) + ")");
  }
  const std::optional<ArmTarget>& target = program_.steps[step].arm(arm);
  if (!target) {
    throw Error("recorder: step " + std::to_string(step) + " does not move the " + arm_name(arm) +
                " arm");
  }
  const int anchor = anchors_[step][arm == Arm::kLeft ? 0 : 1];
  return anchor == kBase
             ? target->T_frame_ee
             : instances_[static_cast<std::size_t>(anchor)].box.pose * target->T_frame_ee;
}

std::vector<std::string> Recorder::warnings() const {
  std::vector<std::string> out;
  for (std::size_t step = 0; step < anchors_.size(); ++step) {
    for (const Arm arm : {Arm::kLeft, Arm::kRight}) {
      const int anchor = anchors_[step][arm == Arm::kLeft ? 0 : 1];
      if (anchor == kBase) continue;
      const LandmarkInstance& instance = instances_[static_cast<std::size_t>(anchor)];
      if (instance.capture_warnings.empty()) continue;
      std::string line = "step " + std::to_string(step) + ", " + arm_name(arm) +
                         " arm: relative to '" + instance.name +
                         "', which was warned about at capture: ";
      for (std::size_t k = 0; k < instance.capture_warnings.size(); ++k)
        line += (k ? "; " : "") + instance.capture_warnings[k];
      out.push_back(line);
    }
  }
  return out;
}

void Recorder::set_frame(std::size_t step, Arm arm, const std::string& frame) {
  const Eigen::Isometry3d T_base_ee = base_pose(step, arm);  // checks step and arm
  int anchor = kBase;
  if (frame != kBaseFrame) {
    if (!program_.landmark(frame)) throw Error("recorder: unknown landmark '" + frame + "'");
    anchor = nearest(T_base_ee.translation(), &frame, std::numeric_limits<double>::infinity());
    if (anchor == kBase) {
      throw Error("recorder: landmark '" + frame + "' was not found in the demonstration scene");
    }
  }
  std::optional<ArmTarget>& target = program_.steps[step].arm(arm);
  target = target_in(anchor, T_base_ee, target->gripper);
  anchors_[step][arm == Arm::kLeft ? 0 : 1] = anchor;
  refresh_demonstrations();
}

}  // namespace lmk
