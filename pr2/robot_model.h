// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A robot's kinematic model from URDF (urdfdom): kinematic chains between two links and forward
// kinematics over revolute, continuous, prismatic and fixed joints.

#include <Eigen/Geometry>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lmk/geometry/random.h"
#include "lmk/geometry/solid.h"
#include "lmk/pbd/robot_interface.h"

namespace lmk {

/// One joint of a chain, as URDF describes it.
/// One link of RobotModel::flat_tree(), with the joint that moves it from its parent.
struct FlatLink {
  std::string link;
  std::string joint;  ///< "" for the root
  int parent = -1;    ///< its index in the flat tree; -1 for the root
  Eigen::Isometry3d T_parent_joint = Eigen::Isometry3d::Identity();
  enum class Motion { kFixed, kRevolute, kPrismatic } motion = Motion::kFixed;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< unit
};

/// Each link of `tree` in the root link's frame, `values[i]` the joint value of link i's joint
/// (ignored for a fixed one); `values` as long as `tree`.
std::vector<Eigen::Isometry3d> flat_poses(const std::vector<FlatLink>& tree,
                                          const std::vector<double>& values);
/// flat_poses()'s `values` from joint values by name: 0 for a joint `joints` does not name.
std::vector<double> flat_values(const std::vector<FlatLink>& tree,
                                const std::map<std::string, double>& joints);

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

/// One collision shape of a link (issue #60): a solid placed in the link's frame.
struct LinkSolid {
  std::string link;
  Eigen::Isometry3d T_link_solid = Eigen::Isometry3d::Identity();
  Solid solid = Solid::sphere(0.01);
};

struct CollisionShapeSettings {
  /// A mesh is covered by spheres over cubic cells of this side (cover_with_spheres, solid.h): its
  /// spheres reach at most cell * sqrt(3) / 2 beyond its surface.
  double mesh_cell = 0.02;
  /// Where a mesh named package://NAME/PATH is looked for: DIR/PATH. Empty: the URDF file's own
  /// directory (a description package holds its meshes beside its urdf/ folder).
  std::string package_dir;
  /// Where package NAME's folder is, before package_dir: on a robot under ROS, its package path
  /// (a robot_description names meshes in its description package). Unset, or "" for a package
  /// it does not know: package_dir.
  std::function<std::string(const std::string& package)> package_path;
  /// Only these links' shapes (empty: every link's): a check that needs the arms alone reads no
  /// other mesh.
  std::vector<std::string> only_links;
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

  /// The root link of the description's tree.
  std::string root_link() const;
  /// The tree flattened for forward kinematics many times a second (a motion check checks
  /// thousands of configurations): every link after its parent. flat_poses() places it.
  std::vector<FlatLink> flat_tree() const;
  /// Every link's pose in the root link's frame with the named joints at the given values (rad,
  /// or m for a prismatic joint) and every other joint at 0. A joint value of a fixed joint is
  /// ignored; a name that is no joint is an error (lmk::Error).
  std::map<std::string, Eigen::Isometry3d> link_poses(
      const std::map<std::string, double>& joints) const;
  /// The links' <collision> shapes (robot_collision.cpp): boxes, cylinders and spheres as they
  /// are, STL meshes covered by spheres. Throws lmk::Error naming the link when a mesh cannot be
  /// read or is of another format. Links without a collision shape have none here.
  std::vector<LinkSolid> collision_solids(const CollisionShapeSettings& settings = {}) const;
  /// Every joint of the tree with the links it joins (which touch by design), by joint name.
  struct TreeJoint {
    std::string name, parent, child;
  };
  std::vector<TreeJoint> tree_joints() const;

  ~RobotModel();
  RobotModel(RobotModel&&) noexcept;
  RobotModel& operator=(RobotModel&&) noexcept;

 private:
  struct Impl;
  explicit RobotModel(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace lmk
