// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pbd/watch.h"

#include <cmath>
#include <cstdio>

#include "lmk/geometry/error.h"
#include "lmk/pbd/internal/execute_step.h"

namespace lmk {
namespace {

// A landmark's move since the plan: its box now, turned within its symmetry to the planned box's
// orientation (a bowl tracked half a turn round about its axis has not moved), and how far.
struct Move {
  std::string name;
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();  ///< base frame: now = motion * then
  double distance = 0.0, angle = 0.0;
};

Move move_of(const LocatedLandmark& planned, Eigen::Isometry3d now, const Symmetry& symmetry) {
  const Eigen::Isometry3d& then = planned.match.box.pose;
  now.linear() = nearest_symmetric_rotation(now.linear(), then.linear(), symmetry);
  Move m;
  m.name = planned.name;
  m.motion = now * then.inverse();
  m.distance = (now.translation() - then.translation()).norm();
  m.angle = Eigen::AngleAxisd(now.linear() * then.linear().transpose()).angle();
  return m;
}

std::string describe_move(const Move& m) {
  char text[160];
  std::snprintf(text, sizeof(text), "'%s' moved %.1f cm, %.0f degrees", m.name.c_str(),
                100.0 * m.distance, m.angle * 180.0 / M_PI);
  return text;
}

// One watching execution: the plan it runs from now, and the checks between the steps.
class Watcher {
 public:
  Watcher(const Program& program, RobotInterface& robot, const KinematicsInterface& kinematics,
          LandmarkWatch& watch, const WatchSettings& watching, const PlanSettings& planning,
          WatchedExecution& out)
      : program_(program),
        robot_(robot),
        kinematics_(kinematics),
        watch_(watch),
        watching_(watching),
        planning_(planning),
        out_(out) {}

  enum class Verdict { kGoOn, kReplanned, kStop };

  // Where the landmarks of the steps from `first_step` on are now; a re-plan from there when one
  // moved, or the stop (the report's error) when one is lost, the watch fails, the settings say
  // stop, or the re-plan is refused.
  Verdict check(std::size_t first_step, const std::string& when) {
    const std::vector<std::string> names = landmarks_used(program_, first_step);
    if (names.empty()) return Verdict::kGoOn;
    std::map<std::string, Eigen::Isometry3d> where;
    const CallResult seen = watch_.observe(names, where);
    if (!seen.ok()) return stop(when + ": cannot watch the landmarks: " + seen.message);
    std::vector<Move> moves;
    for (const std::string& name : names) {
      const auto it = where.find(name);
      if (it == where.end())
        return stop(when + ": landmark '" + name +
                    "' is lost: stopped rather than move towards where it was");
      const Move m =
          move_of(*out_.plan.landmark(name), it->second, program_.landmark(name)->symmetry);
      if (m.distance > watching_.translation_tolerance || m.angle > watching_.rotation_tolerance)
        moves.push_back(m);
    }
    if (moves.empty()) return Verdict::kGoOn;
    std::string moved;
    for (const Move& m : moves) moved += (moved.empty() ? "" : ", ") + describe_move(m);
    if (program_.when_landmark_moves.value_or(watching_.when_moved) == WhenMoved::kStop) {
      out_.noticed.push_back(when + ": " + moved + ": stopped");
      return stop(when + ": " + moved + " since planning: stopped, as the program asks");
    }
    return replan(first_step, when + ": " + moved, moves);
  }

 private:
  Verdict stop(const std::string& why) {
    out_.report.error = why;
    return Verdict::kStop;
  }

  Verdict replan(std::size_t first_step, const std::string& what, const std::vector<Move>& moves) {
    std::vector<LocatedLandmark> located = out_.plan.landmarks;
    for (LocatedLandmark& l : located) {
      for (const Move& m : moves) {
        if (m.name != l.name) continue;
        l.T_base_landmark = m.motion * l.T_base_landmark;
        l.match.box.pose = m.motion * l.match.box.pose;
        l.match.T_scene_capture = m.motion * l.match.T_scene_capture;
      }
    }
    JointState joints;
    const CallResult read = robot_.read_joint_state(joints);
    if (!read.ok()) return stop(what + ": cannot read the joint state to re-plan: " + read.message);
    Plan again =
        replan_from(program_, std::move(located), kinematics_, joints, first_step, planning_);
    if (again.refusal) {
      out_.noticed.push_back(what + ": re-planned, refused");
      return stop(what + ": re-planned from there: refused: " + describe(*again.refusal));
    }
    out_.noticed.push_back(what + ": re-planned the remaining " +
                           std::to_string(again.steps.size()) + " steps");
    out_.plan = std::move(again);
    ++out_.replans;
    return Verdict::kReplanned;
  }

  const Program& program_;
  RobotInterface& robot_;
  const KinematicsInterface& kinematics_;
  LandmarkWatch& watch_;
  const WatchSettings& watching_;
  const PlanSettings& planning_;
  WatchedExecution& out_;
};

}  // namespace

void WatchSettings::validate() const {
  if (!(translation_tolerance > 0.0 && translation_tolerance <= 1.0))
    throw Error("watch: the translation tolerance must be in (0, 1] m");
  if (!(rotation_tolerance > 0.0 && rotation_tolerance <= M_PI))
    throw Error("watch: the rotation tolerance must be in (0, 180] degrees");
}

TrackingWatch::TrackingWatch(const Plan& plan, const std::map<std::string, Landmark>& landmarks,
                             FrameSource frames, TrackSettings settings)
    : frames_(std::move(frames)) {
  settings.find.scene.base_frame = true;
  std::vector<std::shared_ptr<const Landmark>> followed;
  for (const LocatedLandmark& l : plan.landmarks) {
    const auto it = landmarks.find(l.name);
    if (it == landmarks.end()) throw Error("watch: landmark '" + l.name + "' was not loaded");
    followed.push_back(std::make_shared<Landmark>(it->second));
    names_.push_back(l.name);
  }
  tracker_ = std::make_unique<Tracker>(std::move(followed), settings);
  for (std::size_t i = 0; i < plan.landmarks.size(); ++i)
    tracker_->follow_from(i, plan.landmarks[i].match.T_scene_capture);
}

CallResult TrackingWatch::observe(const std::vector<std::string>& /*names*/,
                                  std::map<std::string, Eigen::Isometry3d>& where) {
  PointCloud frame;
  const CallResult got = frames_(frame);
  if (!got.ok()) return got;
  try {
    last_ = tracker_->update(frame);
  } catch (const Error& e) {
    return CallResult::error(e.what());
  }
  for (const TrackedLandmark& t : last_) {
    if (t.match) where[t.name] = t.match->box.pose;
  }
  return CallResult::success();
}

WatchedExecution execute_watching(const Program& program, const Plan& plan, RobotInterface& robot,
                                  const KinematicsInterface& kinematics, LandmarkWatch& watch,
                                  const WatchSettings& watching, const PlanSettings& planning,
                                  const ExecuteSettings& settings) {
  watching.validate();
  WatchedExecution out;
  out.plan = plan;
  if (!may_start(plan, robot, settings, out.report)) return out;
  Watcher watcher(program, robot, kinematics, watch, watching, planning, out);
  std::size_t k = 0;  // the next step of out.plan
  while (k < out.plan.steps.size()) {
    const PlannedStep step = out.plan.steps[k];
    const std::string name = "before " + step_name(step.index, step.phase);
    Watcher::Verdict v = watcher.check(step.index, name);
    if (v == Watcher::Verdict::kStop) return out;
    if (v == Watcher::Verdict::kReplanned) {
      k = 0;  // the new plan starts at this step
      continue;
    }
    if (!send_motions(step, robot, out.report)) return out;
    // A grasp or release where the landmark was: look once more before the fingers move.
    if (step.phase == Phase::kTarget && program.steps[step.index].relative_to_landmark()) {
      v = watcher.check(step.index, name + "'s gripper");
      if (v == Watcher::Verdict::kStop) return out;
      if (v == Watcher::Verdict::kReplanned) {
        k = 0;  // this step again, to the landmark's new place, then its grippers
        continue;
      }
    }
    if (!send_gripper_commands(step, robot, settings, out.report)) return out;
    ++out.report.steps_completed;
    if (settings.progress) settings.progress(out.report.steps_completed, out.report.steps_total);
    ++k;
  }
  out.report.completed = true;
  return out;
}

}  // namespace lmk
