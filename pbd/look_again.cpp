// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pbd/look_again.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/occupancy/tsdf_volume.h"

namespace lmk {
namespace {

std::string format_point(const Eigen::Vector3d& p) {
  char text[64];
  std::snprintf(text, sizeof(text), "(%.2f, %.2f, %.2f)", p.x(), p.y(), p.z());
  return text;
}

// Where the first frame looks: along its optical axis, at the median depth of what it saw.
Eigen::Vector3d first_view_target(const PointCloud& first) {
  const Eigen::Vector3d origin = first.T_cloud_sensor.translation();
  const Eigen::Vector3d axis = first.T_cloud_sensor.linear().col(2);
  std::vector<double> depths;
  for (std::size_t i = 0; i < first.points.size(); i += 7) {
    if (is_finite(first.points[i]))
      depths.push_back(axis.dot(first.points[i].cast<double>() - origin));
  }
  double depth = 1.0;
  if (!depths.empty()) {
    std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
    depth = depths[depths.size() / 2];
  }
  return origin + depth * axis;
}

// The k-th look (from 1) of a missing landmark's pattern: the first view's target turned about
// the vertical through the sensor by +a, -a, +2a, -2a, ...
Look pattern_look(const PointCloud& first, int k, double angle) {
  const int step = alternating_step(k);
  const Eigen::Vector3d origin = first.T_cloud_sensor.translation();
  const Eigen::Vector3d turned =
      origin + Eigen::AngleAxisd(step * angle, Eigen::Vector3d::UnitZ()) *
                   (first_view_target(first) - origin);
  char why[96];
  std::snprintf(why, sizeof(why), "panned %+.0f degrees from the first view",
                step * angle * 180.0 / M_PI);
  return {turned, why};
}

// Where to look next for refusal `refusal`, the `k`-th further look; nothing when looking cannot
// help (an unreachable step).
std::optional<Look> next_look(const Refusal& refusal, const PointCloud& first, int k,
                              const LookAgainSettings& s) {
  if (const auto* doubtful = std::get_if<LandmarkDoubtful>(&refusal)) {
    const Eigen::Vector3d at = doubtful->box.center();
    if (doubtful->competitor.kind == Competitor::Kind::none) {
      return Look{at, "at the doubtful '" + doubtful->landmark + "'"};
    }
    return Look{0.5 * (at + doubtful->competitor.box.center()),
                "between the doubtful '" + doubtful->landmark + "' and its " +
                    setting_name(doubtful->competitor.kind)};
  }
  if (std::holds_alternative<LandmarkNotFound>(refusal)) {
    Look look = pattern_look(first, k, s.pattern_angle);
    look.why =
        "for the missing '" + std::get<LandmarkNotFound>(refusal).landmark + "', " + look.why;
    return look;
  }
  return std::nullopt;
}

}  // namespace

void LookAgainSettings::validate() const {
  if (max_looks < 0 || max_looks > 8) {
    throw Error("look again: " + std::to_string(max_looks) + " looks: must be 0 to 8");
  }
  if (!(pattern_angle > 0.0 && pattern_angle <= 1.0)) {
    throw Error("look again: pattern angle " + std::to_string(pattern_angle) +
                " rad: must be in (0, 1]");
  }
}

LookedPlan plan_looking_again(const Program& program,
                              const std::map<std::string, Landmark>& landmarks,
                              const PointCloud& first, const KinematicsInterface& kinematics,
                              const JointState& start, Eyes& eyes, const PlanSettings& settings,
                              const LookAgainSettings& looking) {
  looking.validate();
  LookedPlan out;
  out.plan = plan(program, landmarks, first, kinematics, start, settings);
  std::vector<PointCloud> more;  // the further frames, in order
  more.reserve(static_cast<std::size_t>(looking.max_looks));
  for (int k = 1; k <= looking.max_looks && out.plan.refusal; ++k) {
    const std::optional<Look> look = next_look(*out.plan.refusal, first, k, looking);
    if (!look) break;
    out.looks.push_back(*look);
    if (settings.progress) settings.progress("looking again " + format_point(look->target));
    PointCloud frame;
    const CallResult seen = eyes.look_at(look->target, frame);
    if (!seen.ok()) {
      out.looks.back().why += " (failed: " + seen.message + ")";
      break;
    }
    more.push_back(std::move(frame));
    std::vector<DepthFrame> fused{{&first}};
    for (const PointCloud& f : more) fused.push_back({&f});
    out.plan = plan(program, landmarks, fuse_frames(fused), kinematics, start, settings);
  }
  return out;
}

std::string describe_looks(const std::vector<Look>& looks) {
  if (looks.empty()) return "";
  std::string out = "after " + std::to_string(looks.size()) + " more look" +
                    (looks.size() == 1 ? "" : "s") + " (";
  for (std::size_t i = 0; i < looks.size(); ++i) {
    out +=
        (i ? "; " : "") + std::string("at ") + format_point(looks[i].target) + ": " + looks[i].why;
  }
  return out + ")";
}

}  // namespace lmk
