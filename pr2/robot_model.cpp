// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pr2/robot_model.h"

#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "lmk/geometry/error.h"
#include "lmk/geometry/input_file.h"
#include "lmk/pr2/internal/robot_model_impl.h"

namespace lmk {

extern const char* const kPr2Urdf;  // pr2_urdf_data.cpp, generated from pr2/data/pr2.urdf

Eigen::Isometry3d detail::to_eigen(const urdf::Pose& pose) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() << pose.position.x, pose.position.y, pose.position.z;
  T.linear() =
      Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
          .normalized()
          .toRotationMatrix();
  return T;
}

namespace {

ChainJoint to_chain_joint(const urdf::Joint& j, const std::string& what) {
  ChainJoint out;
  out.name = j.name;
  switch (j.type) {
    case urdf::Joint::REVOLUTE:
      out.type = "revolute";
      break;
    case urdf::Joint::CONTINUOUS:
      out.type = "continuous";
      break;
    case urdf::Joint::PRISMATIC:
      out.type = "prismatic";
      break;
    case urdf::Joint::FIXED:
      out.type = "fixed";
      break;
    default:
      throw Error(what + ": joint '" + j.name +
                  "' is floating or planar; kinematic chains support revolute, continuous, "
                  "prismatic and fixed joints");
  }
  out.T_parent_joint = detail::to_eigen(j.parent_to_joint_origin_transform);
  const Eigen::Vector3d axis(j.axis.x, j.axis.y, j.axis.z);
  if (out.moves()) {
    if (!(axis.norm() > 0.0)) throw Error(what + ": joint '" + j.name + "' has a zero axis");
    out.axis = axis.normalized();
  }
  if (j.limits) {
    out.lower = j.limits->lower;
    out.upper = j.limits->upper;
    out.max_velocity = j.limits->velocity;
  }
  return out;
}

}  // namespace

KinematicChain::KinematicChain(std::string root, std::string tip, std::vector<ChainJoint> joints)
    : root_(std::move(root)), tip_(std::move(tip)), joints_(std::move(joints)) {
  dof_ = static_cast<std::size_t>(
      std::count_if(joints_.begin(), joints_.end(), [](const ChainJoint& j) { return j.moves(); }));
}

std::vector<JointInfo> KinematicChain::moving_joints() const {
  std::vector<JointInfo> out;
  for (const ChainJoint& j : joints_) {
    if (j.moves()) out.push_back({j.name, j.type, j.lower, j.upper, j.max_velocity});
  }
  return out;
}

std::vector<double> KinematicChain::random_joints(SplitMix64& rng) const {
  std::vector<double> q;
  for (const ChainJoint& j : joints_) {
    if (!j.moves()) continue;
    const bool continuous = j.type == "continuous";
    const double lo = continuous ? -M_PI : j.lower, hi = continuous ? M_PI : j.upper;
    q.push_back(lo + (hi - lo) * rng.uniform01());
  }
  return q;
}

Eigen::Isometry3d KinematicChain::forward(const std::vector<double>& q) const {
  if (q.size() != dof_) {
    throw Error("forward kinematics " + root_ + " -> " + tip_ + ": " + std::to_string(q.size()) +
                " joint values for " + std::to_string(dof_) + " joints");
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  std::size_t k = 0;
  for (const ChainJoint& j : joints_) {
    T = T * j.T_parent_joint;
    if (j.type == "prismatic") {
      T.translate(j.axis * q[k++]);
    } else if (j.moves()) {
      T.rotate(Eigen::AngleAxisd(q[k++], j.axis));
    }
  }
  return T;
}

RobotModel::RobotModel(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
RobotModel::~RobotModel() = default;
RobotModel::RobotModel(RobotModel&&) noexcept = default;
RobotModel& RobotModel::operator=(RobotModel&&) noexcept = default;

RobotModel RobotModel::from_string(const std::string& xml, const std::string& what) {
  auto impl = std::make_unique<Impl>();
  impl->what = what;
  impl->model = urdf::parseURDF(xml);
  if (!impl->model) throw Error(what + ": not a valid URDF robot description");
  return RobotModel(std::move(impl));
}

RobotModel RobotModel::from_file(const std::string& path) {
  RobotModel model = from_string(read_input_file(path, kRobotInput), path);
  model.impl_->dir = std::filesystem::path(path).parent_path().string();
  return model;
}

RobotModel RobotModel::pr2() { return from_string(kPr2Urdf, "lmk's PR2 description"); }

const std::string& RobotModel::name() const { return impl_->model->getName(); }

bool RobotModel::has_link(const std::string& link) const {
  return static_cast<bool>(impl_->model->getLink(link));
}

KinematicChain RobotModel::chain(const std::string& root, const std::string& tip) const {
  const std::string& what = impl_->what;
  for (const std::string& link : {root, tip}) {
    if (!has_link(link)) throw Error(what + ": no link named '" + link + "'");
  }
  std::vector<ChainJoint> joints;
  std::string link = tip;
  while (link != root) {
    const urdf::LinkConstSharedPtr l = impl_->model->getLink(link);
    if (!l->parent_joint) {
      throw Error(what + ": link '" + tip + "' does not descend from '" + root + "'");
    }
    joints.push_back(to_chain_joint(*l->parent_joint, what));
    link = l->parent_joint->parent_link_name;
  }
  std::reverse(joints.begin(), joints.end());
  return KinematicChain(root, tip, std::move(joints));
}

}  // namespace lmk
