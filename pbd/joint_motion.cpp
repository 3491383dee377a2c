// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pbd/joint_motion.h"

#include <algorithm>
#include <cmath>

namespace lmk {
namespace {

// The joint's travel from a to b: the shorter way round for continuous joints.
double signed_travel(const JointInfo& j, double a, double b) {
  return j.continuous() ? std::remainder(b - a, 2.0 * M_PI) : b - a;
}

}  // namespace

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
      p.positions.push_back(from[i] + s * signed_travel(group.joints[i], from[i], to[i]));
    }
    t.points.push_back(std::move(p));
  }
  return t;
}

}  // namespace lmk
