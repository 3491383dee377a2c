// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pr2/pr2_motion_check.h"

#include <set>

namespace lmk {

namespace {

// Whether `p` (base frame) lies within `margin` of the body at its placement (`placed`, and each
// solid's inverse placement, `unplaced`): the links' spheres first, then the solids of the links
// that reach it.
bool on_body(const RobotBody& body, const std::vector<Eigen::Isometry3d>& placed,
             const std::vector<Eigen::Isometry3d>& unplaced, const Eigen::Isometry3d& T_root_base,
             const Eigen::Vector3d& p, double margin) {
  const Eigen::Vector3d q = T_root_base * p;
  for (std::size_t link = 0; link < body.links().size(); ++link) {
    const double reach = body.link_radius(link) + margin;
    if ((body.link_centre(link, placed) - q).squaredNorm() > reach * reach) continue;
    for (std::size_t i : body.link_solids(link)) {
      if (body.solids()[i].solid.signed_distance(unplaced[i] * q) < margin) return true;
    }
  }
  return false;
}

}  // namespace

std::shared_ptr<const RobotBody> pr2_body() {
  static const std::shared_ptr<const RobotBody> body =
      std::make_shared<RobotBody>(std::make_shared<RobotModel>(RobotModel::pr2()));
  return body;
}

std::function<std::shared_ptr<const MotionChecker>(const std::vector<const PointCloud*>&,
                                                   const JointState&)>
pr2_motion_checker(const Pr2Kinematics& kinematics, const Pr2MotionCheckSettings& settings,
                   std::shared_ptr<const RobotBody> body) {
  if (!body) body = pr2_body();
  auto shared_kinematics = std::make_shared<Pr2Kinematics>(kinematics);
  return [shared_kinematics, settings, body](const std::vector<const PointCloud*>& frames,
                                             const JointState& start) {
    // The start's joints the body's model has (a robot's joint state also names its grippers'
    // motors and casters).
    std::set<std::string> known;
    for (const RobotModel::TreeJoint& j : body->model().tree_joints()) known.insert(j.name);
    JointValues state = {{"torso_lift_joint", shared_kinematics->torso_height()}};
    for (std::size_t i = 0; i < start.names.size() && i < start.positions.size(); ++i)
      if (known.count(start.names[i])) state[start.names[i]] = start.positions[i];
    const std::vector<Eigen::Isometry3d> placed = body->place(state);
    std::vector<Eigen::Isometry3d> unplaced;
    for (const Eigen::Isometry3d& T : placed) unplaced.push_back(T.inverse());
    const std::map<std::string, Eigen::Isometry3d> links = body->model().link_poses(state);
    const auto base = links.find("base_link");
    const Eigen::Isometry3d T_root_base =
        base == links.end() ? Eigen::Isometry3d::Identity() : base->second;
    const auto is_robot = [body, placed, unplaced, T_root_base,
                           margin = settings.self_filter_margin](const Eigen::Vector3d& p) {
      return on_body(*body, placed, unplaced, T_root_base, p, margin);
    };
    return std::make_shared<const RobotMotionChecker>(
        body, std::make_shared<CollisionScene>(frames, settings.scene, is_robot),
        *shared_kinematics, state, settings.motion);
  };
}

}  // namespace lmk
