// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What a plan asks before an arm moves (issue #60): does the motion from one joint vector to the
// next keep the arm clear of the scene, of the space the sensor could not see, and of the robot's
// own body; and, where it does not, a path around. The interface is the robot's (lmk::pr2
// implements it over its collision model and the scene's points), so that planning stays generic.

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace lmk {

/// What a motion would touch first.
struct MotionContact {
  std::string link;  ///< the robot's link that would touch
  /// What it would touch: "the scene", "space the sensor could not see" (hidden behind what it
  /// measured), "space no camera has seen" (out of every frame's view, where that counts as
  /// occupied), or "the robot's <link>".
  std::string obstacle;
  /// Signed distance to the obstacle, m: negative, that deep into it; positive, within the padding.
  double distance = 0.0;
  Eigen::Vector3d where = Eigen::Vector3d::Zero();  ///< the deepest point, base frame
  double at = 0.0;  ///< where along the motion, 0 (start) to 1 (end)
};

/// The verdict on one motion.
struct MotionVerdict {
  /// The smallest distance from the arm to anything it must avoid along the motion, m (negative:
  /// how far into it, the padding not counted); +infinity when nothing lies within reach.
  double clearance = 0.0;
  std::optional<MotionContact> contact;  ///< the first contact within the padding, if any
  std::size_t samples = 0;               ///< configurations checked
  bool free() const { return !contact; }
};

/// A path around what a straight motion would touch.
struct MotionPlan {
  bool found = false;
  std::vector<std::vector<double>> waypoints;  ///< joint vectors after the start, the goal last
  double seconds = 0.0;                        ///< planning time
  std::size_t checks = 0;                      ///< configurations the planner checked
  std::string message;  ///< why none was found ("no collision-free path within 2 s")
};

/// Joint values by name (rad, or m for a prismatic joint).
using JointValues = std::map<std::string, double>;

/// Scene points a motion may touch on purpose: those within `radius` of any of `near` (base
/// frame), for the gripper's links only: a grasped object between the fingers, the surface under a
/// place.
struct IntendedContact {
  std::vector<Eigen::Vector3d> near;
  double radius = 0.0;
};

class MotionChecker {
 public:
  virtual ~MotionChecker() = default;
  /// The padding every check keeps, m.
  virtual double padding() const = 0;
  /// Checks the straight joint-space line from `from` to `to` (every joint either names; joints
  /// neither names stay where the checker's robot state holds them), continuous joints the shorter
  /// way round, sampled finely enough that no point of the robot moves more than the padding
  /// between two samples.
  virtual MotionVerdict check_line(const JointValues& from, const JointValues& to,
                                   const IntendedContact& intended = {}) const = 0;
  /// Whether the configuration `joints` (joints not named as the robot stands) puts any link that
  /// the named joints move inside the scene, the space the sensor could not see, or the robot: a
  /// target to move to must not (within the padding it may: it was demonstrated there).
  virtual std::optional<MotionContact> check_pose(const JointValues& joints,
                                                  const IntendedContact& intended = {}) const = 0;
  /// A collision-free path for `group`'s joints from `from` to `to`, the other joints held as in
  /// `from`, within the checker's time budget.
  virtual MotionPlan plan_around(const std::string& group, const JointValues& from,
                                 const JointValues& to,
                                 const IntendedContact& intended = {}) const = 0;
  /// Where the links the path moves pass through space no camera has seen (outside every frame's
  /// view, off the robot, within reach), along the straight joint lines between consecutive states
  /// of `path` (by name, joints not named as the robot stands): places a few centimetres apart,
  /// in the order the arm reaches them, for the head to look at before the arm goes. None for a
  /// checker that knows nothing of views.
  virtual std::vector<Eigen::Vector3d> unseen_along(const std::vector<JointValues>& path) const {
    (void)path;
    return {};
  }
};

/// "(0.62, -0.18, 0.81)": a point for a person, to the centimetre.
std::string format_point(const Eigen::Vector3d& p);

/// One line for a person: "the right forearm would pass 1.4 cm into the scene near (0.62, -0.18,
/// 0.81) m in base_link".
std::string describe(const MotionContact& contact);

}  // namespace lmk
