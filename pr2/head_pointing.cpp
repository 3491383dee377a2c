// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pr2/head_pointing.h"

#include <algorithm>
#include <cmath>

#include "lmk/geometry/error.h"
#include "lmk/pbd/joint_motion.h"

namespace lmk {

std::vector<double> head_joints_looking_at(const Pr2Kinematics& kinematics,
                                           const Eigen::Vector3d& target) {
  const auto head = kinematics.group("head");
  if (!head || head->joints.size() != 2)
    throw Error("head pointing: the robot has no pan-tilt head");
  std::vector<double> q = {0.0, 0.0};
  // The pan axis is vertical and the tilt axis horizontal, and the camera sits close to both: each
  // pass turns pan and then tilt by the angle between the optical axis and the target seen in the
  // camera frame (x right, y down, z forward). A few passes absorb the camera's offset.
  for (int pass = 0; pass < 20; ++pass) {
    Eigen::Isometry3d T_base_camera;
    kinematics.forward("head", q, T_base_camera);
    const Eigen::Vector3d d = T_base_camera.inverse() * target;
    const double pan_step = -std::atan2(d.x(), d.z());  // target to the right: pan clockwise
    const double tilt_step = std::atan2(d.y(), d.z());  // target below: tilt down (positive)
    q[0] += pan_step;
    q[1] += tilt_step;
    for (std::size_t i = 0; i < 2; ++i) {
      q[i] = std::clamp(q[i], head->joints[i].lower, head->joints[i].upper);
    }
    if (std::abs(pan_step) + std::abs(tilt_step) < 1e-6) break;
  }
  return q;
}

CallResult point_head(RobotInterface& robot, const Pr2Kinematics& kinematics,
                      const Eigen::Vector3d& target) {
  const GroupInfo head = *kinematics.group("head");
  JointState state;
  if (const CallResult r = robot.read_joint_state(state); !r.ok()) return r;
  const std::vector<double> goal = head_joints_looking_at(kinematics, target);
  std::vector<double> now;
  for (const JointInfo& j : head.joints) {
    const auto it = std::find(state.names.begin(), state.names.end(), j.name);
    if (it == state.names.end()) return CallResult::error("the joint state lacks '" + j.name + "'");
    now.push_back(state.positions[static_cast<std::size_t>(it - state.names.begin())]);
  }
  const double duration = std::max(0.5, motion_duration(head, now, goal, 0.5));
  return robot.send_trajectory("head", joint_line(head, now, goal, duration, 5));
}

}  // namespace lmk
