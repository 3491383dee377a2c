// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A robot's kinematic model from URDF (urdfdom): kinematic chains between two links and forward
// kinematics over revolute, continuous, prismatic and fixed joints.

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "lmk/geometry/random.h"
#include "lmk/pbd/robot_interface.h"

namespace lmk {

/// One joint of a chain, as URDF describes it.
struct ChainJoint {
  std::string name;
  std::string type;  ///< "revolute", "continuous", "prismatic" or "fixed"
  Eigen::Isometry3d T_parent_joint = Eigen::Isometry3d::Identity();  ///< the joint origin
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();                   ///< unit, in the joint frame
  double lower = 0.0, upper = 0.0, max_velocity = 0.0;
  bool moves() const { return type != "fixed"; }
};

/// The joints from a root link down to a tip link. Joint values are given for the moving joints
/// only, in chain order.
class KinematicChain {
 public:
  KinematicChain(std::string root, std::string tip, std::vector<ChainJoint> joints);

  const std::string& root_link() const { return root_; }
  const std::string& tip_link() const { return tip_; }
  const std::vector<ChainJoint>& joints() const { return joints_; }
  /// The moving joints, in order, as metadata.
  std::vector<JointInfo> moving_joints() const;
  std::size_t dof() const { return dof_; }

  /// Joint values drawn uniformly within each moving joint's limits ([-pi, pi] when continuous).
  std::vector<double> random_joints(SplitMix64& rng) const;

  /// T_root_tip for the given joint values; throws lmk::Error when the count differs from dof().
  Eigen::Isometry3d forward(const std::vector<double>& q) const;

 private:
  std::string root_, tip_;
  std::vector<ChainJoint> joints_;
  std::size_t dof_ = 0;
};

class RobotModel {
 public:
  /// Parses a URDF file; throws lmk::Error naming the file when it is missing or not valid URDF.
  static RobotModel from_file(const std::string& path);
  /// Parses URDF text; `what` names it in messages.
  static RobotModel from_string(const std::string& xml, const std::string& what);
  /// lmk's own PR2 description (pr2/data/pr2.urdf), built into the library.
  static RobotModel pr2();

  const std::string& name() const;
  bool has_link(const std::string& link) const;
  /// The chain from `root` down to `tip`; throws lmk::Error when either link is unknown or `tip`
  /// does not descend from `root`, or a joint on the way is floating or planar.
  KinematicChain chain(const std::string& root, const std::string& tip) const;

  ~RobotModel();
  RobotModel(RobotModel&&) noexcept;
  RobotModel& operator=(RobotModel&&) noexcept;

 private:
  struct Impl;
  explicit RobotModel(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace lmk
