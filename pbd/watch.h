// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Programs that watch (issue #48). A program located its landmarks once, when it was planned; a
// person may move one while the arm is on its way. Before every step, and again before a step's
// gripper grasps or releases, a watching execution asks where the landmarks the remaining steps
// are relative to are now:
// - one moved beyond the tolerance (1 cm or 5 degrees): the remaining steps are planned again from
//   its new pose and the arm's joints now (replan_from: reachability checked before any motion),
//   or the program stops, as the program says (Program::when_landmark_moves, else WatchSettings);
//   a re-plan out of reach stops it too;
// - one lost (the tracker cannot follow it): the program stops;
// - either way it never moves on towards the pose the landmark left.
// What says where the landmarks are is a LandmarkWatch: on a robot, TrackingWatch, the tracker
// (search/tracker.h) over the frames of its camera, in the base frame.

#include <Eigen/Geometry>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "lmk/pbd/execute.h"
#include "lmk/pbd/plan.h"
#include "lmk/search/tracker.h"

namespace lmk {

/// Where a program's landmarks are now.
class LandmarkWatch {
 public:
  virtual ~LandmarkWatch() = default;
  /// Sets `where` to the box pose (base frame) of each of `names` that is in view now; a name
  /// missing from it is lost. An error (no frame) stops the program as a lost landmark does.
  virtual CallResult observe(const std::vector<std::string>& names,
                             std::map<std::string, Eigen::Isometry3d>& where) = 0;
};

/// The robot's watch: each landmark of a plan followed by a Tracker from where the plan found it,
/// through the frames `frames` gives (organised clouds in the base frame, T_cloud_sensor the
/// camera's), one frame per observation.
class TrackingWatch : public LandmarkWatch {
 public:
  using FrameSource = std::function<CallResult(PointCloud& frame)>;
  /// `landmarks` holds each landmark the plan located, by name. Throws lmk::Error when one is
  /// missing, or for bad settings (Tracker). The scene is the base frame: base_frame is forced on.
  TrackingWatch(const Plan& plan, const std::map<std::string, Landmark>& landmarks,
                FrameSource frames, TrackSettings settings = {});
  CallResult observe(const std::vector<std::string>& names,
                     std::map<std::string, Eigen::Isometry3d>& where) override;
  /// The last observation's states, one per landmark of the plan.
  const std::vector<TrackedLandmark>& last() const { return last_; }

 private:
  std::vector<std::string> names_;
  std::unique_ptr<Tracker> tracker_;
  FrameSource frames_;
  std::vector<TrackedLandmark> last_;
};

struct WatchSettings {
  /// A landmark moved when its box centre moved more than this (m) or turned more than
  /// rotation_tolerance from where the plan composed its targets.
  double translation_tolerance = 0.01;
  double rotation_tolerance = 5.0 * M_PI / 180.0;  ///< rad
  /// For programs that do not say (Program::when_landmark_moves).
  WhenMoved when_moved = WhenMoved::kReplan;
  /// Throws lmk::Error naming the bad value.
  void validate() const;
};

struct WatchedExecution {
  ExecutionReport report;
  /// One line per move noticed, in order: "before step 1: 'bin' moved 4.2 cm, 3 degrees:
  /// re-planned the remaining 2 steps".
  std::vector<std::string> noticed;
  std::size_t replans = 0;
  Plan plan;  ///< the plan last executed from: the first, or the last re-plan
};

/// Runs `plan` (of `program`) on `robot` as execute() does, watching the landmarks through
/// `watch` before each step and before each gripper command of a step relative to a landmark.
/// Re-plans use `planning` (its IK settings) and `kinematics`.
WatchedExecution execute_watching(const Program& program, const Plan& plan, RobotInterface& robot,
                                  const KinematicsInterface& kinematics, LandmarkWatch& watch,
                                  const WatchSettings& watching = {},
                                  const PlanSettings& planning = {},
                                  const ExecuteSettings& settings = {});

}  // namespace lmk
