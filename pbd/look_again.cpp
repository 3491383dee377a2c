// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pbd/look_again.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <tuple>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/occupancy/tsdf_volume.h"

namespace lmk {
namespace {

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

// Where to look before the motions of `plan`: at the place, among those its motions would pass
// through unseen, with the most such places near it (one view holds them), leaving out places an
// earlier look in `done` did not show (the head cannot see them); or, refused for touching hidden
// or unseen space, at the contact. Nothing when no look can help.
std::optional<Look> motion_look(const Plan& plan, const std::vector<Look>& done) {
  constexpr double kOneView = 0.4;  // m: unseen places this near each other fit in one view
  if (const auto* blocked = plan.refusal ? std::get_if<Blocked>(&*plan.refusal) : nullptr) {
    const MotionContact& c = blocked->contact;
    if (c.obstacle.rfind("space ", 0) != 0) return std::nullopt;
    for (const Look& l : done)
      if ((l.target - c.where).norm() < kOneView) return std::nullopt;
    return Look{c.where, "where step " + std::to_string(blocked->step) + "'s " +
                             arm_name(blocked->arm) + " arm would touch " + c.obstacle};
  }
  if (plan.refusal) return std::nullopt;
  std::vector<std::pair<Eigen::Vector3d, std::string>> places;  // with the motion's name
  for (const PlannedStep& step : plan.steps) {
    for (const PlannedArm& a : step.arms) {
      for (const Eigen::Vector3d& p : a.unseen) {
        const bool looked = std::any_of(done.begin(), done.end(), [&](const Look& l) {
          return (l.target - p).norm() < kOneView;
        });
        if (!looked)
          places.emplace_back(p, "step " + std::to_string(step.index) + "'s " + arm_name(a.arm));
      }
    }
  }
  std::size_t best = 0, best_count = 0;
  Eigen::Vector3d best_sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < places.size(); ++i) {
    std::size_t count = 0;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const auto& [q, name] : places) {
      if ((q - places[i].first).norm() > kOneView) continue;
      ++count;
      sum += q;
    }
    if (count > best_count) std::tie(best, best_count, best_sum) = std::tie(i, count, sum);
  }
  if (best_count == 0) return std::nullopt;
  return Look{best_sum / static_cast<double>(best_count),
              "where " + places[best].second + " arm would pass through space no camera has seen"};
}

}  // namespace

void LookAgainSettings::validate() const {
  if (max_looks < 0 || max_looks > 8) {
    throw Error("look again: " + std::to_string(max_looks) + " looks: must be 0 to 8");
  }
  if (unseen_looks < 0 || unseen_looks > 8) {
    throw Error("look again: " + std::to_string(unseen_looks) +
                " looks where motions go unseen: must be 0 to 8");
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
  PointCloud searched;           // the first frame fused with the landmarks' further frames
  const PointCloud* search_scene = &first;
  // Takes the frame `look` asks for and plans again with every frame for the motion check, and
  // with it fused into the search's scene when `for_search`; false when the eyes failed.
  const auto look_and_plan = [&](const Look& look, bool for_search) {
    out.looks.push_back(look);
    if (settings.progress) settings.progress("looking again " + format_point(look.target));
    PointCloud frame;
    const CallResult seen = eyes.look_at(look.target, frame);
    if (!seen.ok()) {
      out.looks.back().why += " (failed: " + seen.message + ")";
      return false;
    }
    more.push_back(std::move(frame));
    // The motion check knows the frames as the sensor took them, the search their fusion.
    std::vector<const PointCloud*> frames{&first};
    for (const PointCloud& f : more) frames.push_back(&f);
    if (for_search) {
      std::vector<DepthFrame> fused;
      for (const PointCloud* f : frames) fused.push_back({f});
      searched = fuse_frames(fused);
      search_scene = &searched;
    }
    out.plan = plan(program, landmarks, *search_scene, kinematics, start, settings, frames);
    return true;
  };
  for (int k = 1; k <= looking.max_looks && out.plan.refusal; ++k) {
    const std::optional<Look> look = next_look(*out.plan.refusal, first, k, looking);
    if (!look) break;
    if (!look_and_plan(*look, true)) return out;
  }
  // Where the motions would go unseen, while a look shows somewhere new. The landmarks are
  // settled: these frames only tell the motion check what stands in the arm's way.
  const std::size_t landmark_looks = out.looks.size();
  for (int k = 1; k <= looking.unseen_looks && settings.motion_checker; ++k) {
    const std::optional<Look> look = motion_look(
        out.plan, std::vector<Look>(out.looks.begin() + static_cast<std::ptrdiff_t>(landmark_looks),
                                    out.looks.end()));
    if (!look || !look_and_plan(*look, false)) break;
  }
  // Then back at the first view, where the landmarks are, for whoever watches them next.
  if (out.looks.size() > landmark_looks) {
    out.looks.push_back({first_view_target(first), "back at the first view"});
    PointCloud frame;
    const CallResult seen = eyes.look_at(out.looks.back().target, frame);
    if (!seen.ok()) out.looks.back().why += " (failed: " + seen.message + ")";
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
