// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pr2/trajectory_contacts.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lmk/geometry/error.h"
#include "lmk/geometry/stl_mesh.h"
#include "lmk/pbd/joint_motion.h"

namespace lmk {

namespace {

// The tool frame's position with `group` at `q`, or nothing where FK fails.
std::optional<Eigen::Vector3d> tool_position(const Pr2Kinematics& kinematics,
                                             const std::string& group,
                                             const std::vector<double>& q) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  if (!kinematics.forward(group, q, T).ok()) return std::nullopt;
  return T.translation();
}

}  // namespace

RobotMotionChecker contact_checker(std::shared_ptr<const RobotBody> body,
                                   std::shared_ptr<const CollisionScene> world,
                                   const Pr2Kinematics& kinematics, const JointValues& state,
                                   const TrajectoryContactSettings& settings) {
  if (!(settings.step > 0.0)) throw Error("trajectory contacts: the step must be positive");
  MotionCheckSettings check;
  check.padding = settings.step;  // how far beyond a link the world is looked at; contact is < 0
  check.self_padding = 0.0;
  return RobotMotionChecker(std::move(body), std::move(world), kinematics, state, check);
}

std::optional<MotionContact> trajectory_contact(const RobotMotionChecker& checker,
                                                const Pr2Kinematics& kinematics,
                                                const std::string& group, const JointValues& state,
                                                const JointTrajectory& trajectory,
                                                const TrajectoryContactSettings& settings) {
  if (!(settings.step > 0.0)) throw Error("trajectory contacts: the step must be positive");
  const std::optional<GroupInfo> info = kinematics.group(group);
  if (!info) throw Error("trajectory contacts: no group named '" + group + "'");
  if (trajectory.points.empty()) return std::nullopt;
  const std::vector<JointInfo>& joints = info->joints;
  // The joint vectors the arm passes: where it stands, then every point as sent.
  std::vector<std::vector<double>> points;
  std::vector<double> times = {0.0};
  std::vector<double> now(joints.size());
  for (std::size_t i = 0; i < joints.size(); ++i) now[i] = state.at(joints[i].name);
  points.push_back(now);
  for (const JointTrajectory::Point& p : trajectory.points) {
    // A continuous joint turns the shorter way from each point to the next, as the robot's
    // controller (and SimulatedPr2's check) takes it.
    std::vector<double> q = p.positions;
    const std::vector<double>& last = points.back();
    for (std::size_t i = 0; i < joints.size(); ++i)
      if (joints[i].continuous()) q[i] = last[i] + signed_travel(joints[i], last[i], q[i]);
    points.push_back(q);
    times.push_back(p.time_from_start);
  }
  IntendedContact intended;
  intended.radius = settings.intended_radius;
  for (const std::vector<double>* end : {&points.front(), &points.back()})
    if (const auto p = tool_position(kinematics, group, *end)) intended.near.push_back(*p);
  const double duration = std::max(times.back(), 1e-9);
  JointValues q;  // the group's joints; the rest stand as in `state`
  for (std::size_t k = 1; k < points.size(); ++k) {
    double span = 0.0;  // how far any point can move on this segment, m
    for (std::size_t i = 0; i < joints.size(); ++i)
      span += std::abs(points[k][i] - points[k - 1][i]) * checker.lever(joints[i].name);
    const int steps = std::max(1, static_cast<int>(std::ceil(span / settings.step)));
    for (int s = (k == 1 ? 0 : 1); s <= steps; ++s) {
      const double t = static_cast<double>(s) / steps;
      for (std::size_t i = 0; i < joints.size(); ++i)
        q[joints[i].name] = points[k - 1][i] + t * (points[k][i] - points[k - 1][i]);
      if (std::optional<MotionContact> c = checker.check_pose(q, intended)) {
        c->at = (times[k - 1] + t * (times[k] - times[k - 1])) / duration;
        if (c->obstacle == "the scene") c->obstacle = "the world";
        return c;
      }
    }
  }
  return std::nullopt;
}

std::string describe_touch(const MotionContact& c) {
  char text[320];
  std::snprintf(text, sizeof(text),
                "link %s went %.1f mm into %s near (%.2f, %.2f, %.2f) m in base_link, %.0f%% of "
                "the way",
                c.link.c_str(), 1000.0 * std::max(0.0, -c.distance), c.obstacle.c_str(),
                c.where.x(), c.where.y(), c.where.z(), 100.0 * c.at);
  return text;
}

std::shared_ptr<const CollisionScene> ground_truth_scene(
    const std::vector<Eigen::Vector3d>& vertices, const std::vector<Eigen::Vector3i>& triangles,
    double spacing) {
  const StlMesh mesh{vertices, triangles};
  PointCloud cloud;
  for (const Eigen::Vector3d& p : mesh_surface_points(mesh, spacing))
    cloud.points.push_back(p.cast<float>());
  cloud.width = static_cast<std::uint32_t>(cloud.points.size());
  cloud.height = 1;
  CollisionSceneSettings settings;
  settings.unknown_is_occupied = false;  // an unorganised cloud hides nothing anyway
  settings.voxel = spacing;
  return std::make_shared<CollisionScene>(cloud, settings);
}

}  // namespace lmk
