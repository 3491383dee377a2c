// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pbd/joint_motion.h"

#include <algorithm>
#include <cmath>
#include <numeric>

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
  // Each line's seconds: its share at full speed, but at least a hundredth of an equal share, so
  // that a line that takes (almost) no time still has increasing times; then all scaled to sum to
  // `duration`, so that the path ends when its caller holds the arm. (A millisecond floor added
  // after the fact once ran a path past the hold at its end: the demo's task 3, issue #63.)
  const double lines = static_cast<double>(waypoints.size());
  std::vector<double> seconds;
  const std::vector<double>* at = &from;
  for (const std::vector<double>& next : waypoints) {
    const double share =
        full_speed > 0.0 ? motion_duration(group, *at, next, 1.0) / full_speed : 1.0 / lines;
    seconds.push_back(std::max(share, 0.01 / lines));
    at = &next;
  }
  const double total = std::accumulate(seconds.begin(), seconds.end(), 0.0);
  for (double& s : seconds) s *= duration / total;
  JointTrajectory t;
  for (const JointInfo& j : group.joints) t.joint_names.push_back(j.name);
  double start = 0.0;
  at = &from;
  for (std::size_t k = 0; k < waypoints.size(); ++k) {
    JointTrajectory line = joint_line(group, *at, waypoints[k], seconds[k], per_line);
    for (JointTrajectory::Point& p : line.points) {
      p.time_from_start += start;
      t.points.push_back(std::move(p));
    }
    start += seconds[k];
    at = &waypoints[k];
  }
  t.points.back().time_from_start = duration;  // not a rounding of the sum either side of it
  return t;
}

}  // namespace lmk
