// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// MotionChecker (pbd/motion_check.h) over a robot's body and a scene (issue #60): every sampled
// configuration of a motion is checked against the scene's points and hidden space
// (pbd/collision_scene.h) and against the robot's own links, within a padding; a motion that
// would touch is planned around with OMPL's RRT-Connect in the group's joint space, then
// shortened and smoothed, within a budget of time and of configurations checked
// (pr2/joint_space_planner.h).

#include <cstdint>
#include <map>
#include <memory>

#include "lmk/pbd/collision_scene.h"
#include "lmk/pbd/motion_check.h"
#include "lmk/pbd/robot_interface.h"
#include "lmk/pr2/robot_body.h"

namespace lmk {

/// The paddings a person may ask for (`--padding`, the page's `padding`), m: a millimetre, within
/// the collision model's fit, to 20 cm, beyond which a PR2 reaches nothing on a table.
inline constexpr double kMinPadding = 0.001, kMaxPadding = 0.2;

struct MotionCheckSettings {
  double padding = 0.02;  ///< m kept from the scene
  /// m kept between the robot's own links: its shapes are fitted within millimetres, and its arms
  /// pass close by design (a hand-over, both hands on one object)
  double self_padding = 0.01;
  double planning_time = 2.0;  ///< s allowed to plan around an obstacle
  /// Configurations a plan around an obstacle may check, search and smoothing together: the
  /// budget that does not depend on the machine. The default is over twice what 95% of
  /// `lmk bench --motion`'s plans check, about 1.2 s on a 2-core machine.
  std::size_t planning_checks = 20000;
  bool self_collisions = true;  ///< check the arm against the robot's own body
  /// The planner's random seed: the same inputs, the same path, unless the time ran out first.
  std::uint64_t seed = 1;
};

class RobotMotionChecker : public MotionChecker {
 public:
  /// `kinematics` gives the groups' joints and limits; `state`: where every other joint is (the
  /// torso, the head, the other arm), by name. Throws lmk::Error for a non-positive padding or
  /// planning budget.
  RobotMotionChecker(std::shared_ptr<const RobotBody> body,
                     std::shared_ptr<const CollisionScene> scene,
                     const KinematicsInterface& kinematics, JointValues state,
                     const MotionCheckSettings& settings = {});

  /// The same checker with the robot standing at `state` instead (by name; joints it does not name
  /// as before): no lever is measured again.
  RobotMotionChecker with_state(const JointValues& state) const;

  double padding() const override { return settings_.padding; }
  MotionVerdict check_line(const JointValues& from, const JointValues& to,
                           const IntendedContact& intended = {}) const override;
  MotionPlan plan_around(const std::string& group, const JointValues& from, const JointValues& to,
                         const IntendedContact& intended = {}) const override;
  std::optional<MotionContact> check_pose(const JointValues& joints,
                                          const IntendedContact& intended = {}) const override;
  std::vector<Eigen::Vector3d> unseen_along(const std::vector<JointValues>& path) const override;

  /// What each link (by the body's index) must keep from the scene and from the robot's other
  /// links, m.
  struct Needs {
    std::vector<double> scene, self;
  };
  /// What the moving links must keep along a motion from `from` to `to` (whole joint states): the
  /// paddings, or half of what a link keeps at either end where that is less. A demonstration that
  /// put the forearm 1 cm from a shelf may go there, but comes no nearer on the way, and only near
  /// that end (needs_at); an end inside something still refuses.
  Needs needs_between(const JointValues& from, const JointValues& to,
                      const std::vector<char>& moving, const IntendedContact* intended) const;

  /// One configuration (joints not named as in the state), the links in `moving` (by the body's
  /// link index) checked against what they must keep (`needs`; unset: the paddings): the nearest
  /// approach (its distance in `clearance`) and the deepest contact, if any. `measured`: each
  /// link's nearest approach, up to the paddings.
  std::optional<MotionContact> check_state(
      const JointValues& joints, const std::vector<char>& moving, const IntendedContact* intended,
      double* clearance = nullptr, const Needs* needs = nullptr, Needs* measured = nullptr) const;
  /// The links (by the body's index) that move when any of `joints` does.
  std::vector<char> links_moved_by(const std::vector<std::string>& joints) const;
  /// An upper bound of how far any point of the body moves per radian (or metre) of `joint`.
  double lever(const std::string& joint) const;

 private:
  JointValues merged(const JointValues& joints) const;
  /// The joint's travel from a to b as joint_line moves it (signed_travel); a joint no group
  /// names, straight.
  double travel(const std::string& joint, double a, double b) const;
  /// Needs of nothing but not going inside: near a motion's ends (kEndZone of travel), where a
  /// link already within the padding must be free to leave or arrive.
  Needs touching_only() const;
  /// What the links need `from_end` m of travel from the nearer end of a motion whose ends allow
  /// `ends_allow` (needs_between): nothing but not going inside within the end zone, then one
  /// more centimetre per centimetre of travel, up to the paddings.
  Needs needs_at(const Needs& ends_allow, double from_end) const;
  /// How far any point of the body moves from `a` to `b` at most (sum of |dq| times the levers).
  double sweep(const JointValues& a, const JointValues& b) const;
  std::shared_ptr<const RobotBody> body_;
  std::shared_ptr<const CollisionScene> scene_;
  std::map<std::string, GroupInfo> groups_;
  std::map<std::string, JointInfo> joint_info_;
  std::map<std::string, std::vector<char>> moved_by_;
  std::map<std::string, double> lever_;
  std::vector<std::size_t> gripper_links_;  // links whose contact with intended points is allowed
  JointValues state_;
  Eigen::Isometry3d T_base_root_ = Eigen::Isometry3d::Identity();
  MotionCheckSettings settings_;
};

}  // namespace lmk
