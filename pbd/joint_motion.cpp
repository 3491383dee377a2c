// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pbd/joint_motion.h"

#include <algorithm>
#include <cmath>

namespace lmk {

double signed_travel(const JointInfo& j, double a, double b) {
  return j.continuous() ? std::remainder(b - a, 2.0 * M_PI) : b - a;
}

double random_joint(const JointInfo& j, SplitMix64& rng) {
  const double lo = j.continuous() ? -M_PI : j.lower, hi = j.continuous() ? M_PI : j.upper;
  return lo + (hi - lo) * rng.uniform01();
}

std::vector<double> random_joints(const GroupInfo& group, SplitMix64& rng) {
  std::vector<double> q;
  for (const JointInfo& j : group.joints) q.push_back(random_joint(j, rng));
  return q;
}

double motion_duration(const GroupInfo& group, const std::vector<double>& from,
                       const std::vector<double>& to, double speed_fraction) {
  double duration = 0.0;
  for (std::size_t i = 0; i < group.joints.size(); ++i) {
    const JointInfo& j = group.joints[i];
    if (j.max_velocity <= 0.0) continue;
    const double travel = std::abs(signed_travel(j, from[i], to[i]));
    duration = std::max(duration, travel / (speed_fraction * j.max_velocity));
  }
  return duration;
}

JointTrajectory joint_line(const GroupInfo& group, const std::vector<double>& from,
                           const std::vector<double>& to, double duration, int points) {
  JointTrajectory t;
  for (const JointInfo& j : group.joints) t.joint_names.push_back(j.name);
  for (int k = 1; k <= points; ++k) {
    const double s = static_cast<double>(k) / points;
    JointTrajectory::Point p;
    p.time_from_start = s * duration;
    for (std::size_t i = 0; i < group.joints.size(); ++i) {
      // The last point is the target itself: from + (to - from) may round past a joint limit the
      // target sits on.
      const bool last = k == points && !group.joints[i].continuous();
      p.positions.push_back(last ? to[i]
                                 : from[i] + s * signed_travel(group.joints[i], from[i], to[i]));
    }
    t.points.push_back(std::move(p));
  }
  return t;
}

double path_duration(const GroupInfo& group, const std::vector<double>& from,
                     const std::vector<std::vector<double>>& waypoints, double speed_fraction) {
  double total = 0.0;
  const std::vector<double>* at = &from;
  for (const std::vector<double>& next : waypoints) {
    total += motion_duration(group, *at, next, speed_fraction);
    at = &next;
  }
  return total;
}

JointTrajectory joint_path(const GroupInfo& group, const std::vector<double>& from,
                           const std::vector<std::vector<double>>& waypoints, double duration,
                           int points) {
  if (waypoints.empty()) return joint_line(group, from, from, duration, points);
  const double full_speed = path_duration(group, from, waypoints, 1.0);
  const int per_line = std::max(
      1, (points + static_cast<int>(waypoints.size()) - 1) / static_cast<int>(waypoints.size()));
  JointTrajectory t;
  for (const JointInfo& j : group.joints) t.joint_names.push_back(j.name);
  double start = 0.0;
  const std::vector<double>* at = &from;
  for (const std::vector<double>& next : waypoints) {
    // Lines that take no time at full speed still get an equal share, so times keep increasing.
    const double share = full_speed > 0.0 ? motion_duration(group, *at, next, 1.0) / full_speed
                                          : 1.0 / static_cast<double>(waypoints.size());
    const double seconds = std::max(share * duration, 1e-3);
    JointTrajectory line = joint_line(group, *at, next, seconds, per_line);
    for (JointTrajectory::Point& p : line.points) {
      p.time_from_start += start;
      t.points.push_back(std::move(p));
    }
    start += seconds;
    at = &next;
  }
  return t;
}

}  // namespace lmk
