// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Planning a PbD program in a new scene (paper, Section III-B, and the original PR2 PbD's
// execution): locate every landmark the program uses, compose each landmark-relative target with
// where the landmark is now, and solve IK for every step before anything moves. A plan that
// cannot be carried out whole carries its refusal instead, so that a robot never starts a program
// it cannot finish.
//
//   T_base_ee = T_base_landmark * T_landmark_ee

#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "lmk/landmark/landmark.h"
#include "lmk/pbd/approach.h"
#include "lmk/pbd/motion_check.h"
#include "lmk/pbd/program.h"
#include "lmk/pbd/robot_interface.h"
#include "lmk/search/find_landmark.h"

namespace lmk {

/// Refusal: a landmark the program needs is not in the scene (or no instance passes the policy).
struct LandmarkNotFound {
  std::string landmark;
  std::string reason;  ///< what the search turned down, for a person
};

/// Refusal: a landmark the program needs was found, but no instance the policy allows is sure
/// enough: its calibrated confidence (match_confidence.h) is below PlanSettings::min_confidence.
/// A wrong motion is worse than a refusal.
struct LandmarkDoubtful {
  std::string landmark;
  double confidence = 0.0;      ///< the preferred instance's (NaN: no calibration for the metric)
  double min_confidence = 0.0;  ///< the cut it missed
  Competitor competitor;        ///< what competes with it
  std::string doubt;            ///< the confidence's own line: why it is low
  Box box;                      ///< the preferred instance's box, base frame
};

/// Refusal: a step's target is out of the arm's reach (or its joint limits).
struct Unreachable {
  std::size_t step = 0;
  Arm arm = Arm::kRight;
  Phase phase = Phase::kTarget;  ///< the step's target, or its approach or retreat
  std::string reason;
};

/// Refusal (issue #60): a step's motion would touch the scene, space the sensor could not see, or
/// the robot itself, and no collision-free path was found around it.
struct Blocked {
  std::size_t step = 0;
  Arm arm = Arm::kRight;
  Phase phase = Phase::kTarget;  ///< the motion to the step's target, or its approach or retreat
  MotionContact contact;         ///< what the straight motion would touch first
  std::string planner;           ///< why no path around it was found
};

using Refusal = std::variant<LandmarkNotFound, LandmarkDoubtful, Unreachable, Blocked>;

/// "landmark-not-found", "landmark-doubtful", "unreachable" or "collision".
const char* refusal_kind(const Refusal& refusal);
/// One line for a person: "landmark 'rack' not found: no candidate pose ...", "landmark 'rack'
/// doubtful: confidence 0.41 below 0.90: a pose 8 cm along the box's x fits within the noise",
/// "step 3, right arm: unreachable: ...", "step 3, right arm: link r_forearm_link would pass 1.4 cm
/// into the scene near (0.62, -0.18, 0.81) m in base_link, 40% of the way; no collision-free path
/// within 2 s"; "step 3's approach, right arm: ..." for the motion before a grasp.
std::string describe(const Refusal& refusal);

/// A landmark where it was found in the scene.
struct LocatedLandmark {
  std::string name;
  /// The box pose to compose targets with: the match's box, turned within the landmark's symmetry
  /// to the orientation nearest the demonstration.
  Eigen::Isometry3d T_base_landmark = Eigen::Isometry3d::Identity();
  Match match;               ///< the instance chosen
  std::size_t found = 0;     ///< matches the search returned
  std::size_t eligible = 0;  ///< of those, the ones the policy allowed
  InstancePolicy policy = InstancePolicy::kBestError;
  double seconds = 0.0;  ///< the search's time
  std::string metric;    ///< the search's error metric: the unit of match.error
};

/// One arm's part of a planned step.
struct PlannedArm {
  Arm arm = Arm::kRight;
  std::string frame;                                            ///< "base" or the landmark
  Eigen::Isometry3d T_base_ee = Eigen::Isometry3d::Identity();  ///< the target in the base frame
  IkResult ik;
  JointTrajectory trajectory;  ///< from the previous step's joints to the solution
  GripperAction gripper = GripperAction::kOpen;
  /// With motions checked (PlanSettings::motion_checker): the smallest distance the motion keeps
  /// from the scene and the robot, m (a lower bound beyond a few centimetres); NaN unchecked.
  double clearance = std::numeric_limits<double>::quiet_NaN();
  /// Whether the straight joint line would have touched, and the motion goes around instead.
  bool planned_around = false;
  /// The path around: its planning time, s, and the configurations it checked (0 for a line).
  double planning_seconds = 0.0;
  std::size_t planning_checks = 0;
  /// What the motion may touch on purpose: scene points near the tool frame at its start and at its
  /// target (the object grasped, the surface placed on), for the gripper's links only.
  IntendedContact intended;
  /// With motions checked: where the arm passes through space no camera has seen on its way
  /// (MotionChecker::unseen_along), in the order it gets there; a look there first
  /// (plan_looking_again) shows what stands in it. Empty: every place it passes was in view.
  std::vector<Eigen::Vector3d> unseen;
};

/// One motion of the arms: to a program step's targets, or its approach or retreat (approach.h).
/// The robot moves, then sets the grippers.
struct PlannedStep {
  std::size_t index = 0;  ///< the program step
  Phase phase = Phase::kTarget;
  std::vector<PlannedArm> arms;
  double duration = 0.0;  ///< s; both arms move together
};

struct Plan {
  std::string program;
  std::vector<LocatedLandmark> landmarks;
  std::vector<PlannedStep> steps;  ///< every step, or none when refused
  /// The arm joints the plan starts from, by joint name: execution checks the robot is there.
  std::map<std::string, double> start;
  std::optional<Refusal> refusal;
  /// One line per landmark some step uses whose capture check warned (CaptureFindings::warned,
  /// issue #59): "landmark 'rack' (steps 1, 3) was warned about at capture: slides ...". Such a
  /// landmark's confidence weighs the warning; a plan acts on it when the confidence passes the
  /// cut, and says so here, refused or not.
  std::vector<std::string> warnings;
  bool valid() const { return !refusal; }
  const LocatedLandmark* landmark(const std::string& name) const;
};

struct PlanSettings {
  /// The landmark search. The scene is in the robot base frame (base_frame is forced on).
  FindSettings find;
  /// Step 1 of the paper's Algorithm 1, the work volume, when find.scene.work_volume is unset: the
  /// space the arms can act in, base frame. The default, x 0-1.3 m, y -1 to 1 m, z 0-1.9 m, holds a
  /// PR2's reach and leaves out the floor, whose plane the flat parts of many landmarks would
  /// otherwise match all over (a control panel's face around its dial).
  Box workspace = Box(Eigen::Translation3d(0.65, 0.0, 0.85) * Eigen::Isometry3d::Identity(),
                      Eigen::Vector3d(1.3, 2.0, 1.9));
  /// The instance policy for landmarks whose program entry sets none.
  InstancePolicy policy = InstancePolicy::kBestError;
  /// Instances need at least this calibrated confidence (match_confidence.h) to be acted on; when
  /// none of a landmark's does, the plan is refused (LandmarkDoubtful) before anything moves. 0
  /// acts on any match, as before confidences existed.
  double min_confidence = kDefaultMinConfidence;
  /// kDemonstratedHeight: an instance's box centre must be within this of the demonstrated height
  /// (about an inch: a table is not a box standing on it).
  double height_tolerance = 0.03;
  /// When a step is out of reach with the preferred instance of its landmark, try the landmark's
  /// other eligible instances in policy order before refusing.
  bool try_other_instances = true;
  /// Joint speeds are kept to this fraction of each joint's limit.
  double speed_fraction = 0.5;
  double min_step_duration = 1.0;  ///< s; no motion is planned faster than this
  int waypoints = 10;              ///< points per joint trajectory
  /// Progress lines for long runs ("locating 'rack'", ...); unset: silent.
  std::function<void(const std::string&)> progress;
  /// Checks every arm motion against the scene and the robot's own body before anything moves
  /// (issue #60), built from the frames the robot saw (base frame: the one the plan searched,
  /// then any further ones) and its joints at the start: lmk::pr2's pr2_motion_checker() for a
  /// PR2. Unset: motions are not checked. replan_from, which has no frame, checks against the
  /// robot's own body only.
  std::function<std::shared_ptr<const MotionChecker>(const std::vector<const PointCloud*>& frames,
                                                     const JointState& start)>
      motion_checker;
  /// Scene points within this of the tool frame at a motion's start and target are what the motion
  /// means to touch (PlannedArm::intended), m.
  double intended_contact_radius = 0.08;
  /// A grasp is approached, and a release backed off, this far along the gripper's axis
  /// (approach.h), m: a motion of its own (PlannedStep::phase). 0: none; a program's own approach
  /// counts.
  double approach = 0.10;
};

/// The warnings of Plan::warnings: for each landmark of `landmarks` that a step of `program` is
/// relative to and whose capture check warned, one line naming it, the steps and the warnings.
std::vector<std::string> capture_warnings(const Program& program,
                                          const std::map<std::string, Landmark>& landmarks);

/// `group`'s joint values in its order, from `positions` by name (Plan::start, a joint state's):
/// where the group stands. Throws lmk::Error naming a joint `positions` lacks.
std::vector<double> group_start(const GroupInfo& group,
                                const std::map<std::string, double>& positions);

/// The landmarks a program uses, loaded from their .lmk files, by name. Relative file names are
/// taken relative to `program_dir`. Throws lmk::Error naming the landmark and file that fail.
std::map<std::string, Landmark> load_program_landmarks(const Program& program,
                                                       const std::string& program_dir);

/// Plans `program` in `scene` (a cloud in the robot base frame, with T_cloud_sensor the sensor's
/// pose), for a robot whose joints are at `start` now. `landmarks` holds each landmark the program
/// declares, by name. Only landmarks some step uses are searched for. Never throws for a refusal:
/// the plan carries it. Throws lmk::Error for bad input (a declared landmark missing from
/// `landmarks`, an arm group the kinematics lacks, a start state missing a joint).
/// `motion_frames`: the frames the motion check knows (base frame, organised), when not `scene`
/// alone: every frame the head took, what any of them saw is known to it. Give the sensor's own
/// frames when `scene` is their fusion: a fusion's image lacks what no frame's surface explains,
/// where the sensor's says what it could not measure. A motion that passes through space no
/// frame had in view says where (PlannedArm::unseen) and the plan warns.
Plan plan(const Program& program, const std::map<std::string, Landmark>& landmarks,
          const PointCloud& scene, const KinematicsInterface& kinematics, const JointState& start,
          const PlanSettings& settings = {},
          const std::vector<const PointCloud*>& motion_frames = {});

/// Plans `program` again from step `first_step` on, with its landmarks where `located` says and
/// nothing searched: what a watching execution (watch.h) does when a landmark moved. Targets are
/// composed and every remaining step's IK solved from the joints `start`, as plan() does; a step
/// out of reach refuses the plan (Unreachable). The plan's steps keep their program indices.
/// Throws lmk::Error for a remaining step relative to a landmark `located` lacks.
Plan replan_from(const Program& program, std::vector<LocatedLandmark> located,
                 const KinematicsInterface& kinematics, const JointState& start,
                 std::size_t first_step, const PlanSettings& settings = {});

}  // namespace lmk
