// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pr2/robot_motion_checker.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_set>

#include "lmk/geometry/error.h"
#include "lmk/geometry/random.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/pbd/joint_motion.h"
#include "lmk/pr2/joint_space_planner.h"

namespace lmk {

namespace {

constexpr int kLeverSamples = 64;  // random configurations the levers are bounded over
constexpr double kLeverMargin = 1.1;
// A link near something at either end of a motion must keep this share of that distance on the way.
constexpr double kEndClearanceShare = 0.5;
// Within this much travel of either end (m, the farthest any point moved), a link need only stay
// out of things: it leaves a grasp, or arrives at one, within the padding by design.
constexpr double kEndZone = 0.05;
// Unseen places along a motion are judged one per cube of this side (m), at states no farther
// apart than it moves any point: where to look needs no finer answer.
constexpr double kUnseenCell = 0.05;

// The kUnseenCell cube holding `p`, as one number: 21 bits a coordinate, ±52 km at 5 cm.
std::uint64_t cell_key(const Eigen::Vector3d& p) {
  constexpr std::int64_t kOffset = std::int64_t{1} << 20;
  std::uint64_t key = 0;
  for (int a = 0; a < 3; ++a) {
    const auto c = static_cast<std::int64_t>(std::floor(p[a] / kUnseenCell)) + kOffset;
    key = (key << 21) | (static_cast<std::uint64_t>(c) & ((std::uint64_t{1} << 21) - 1));
  }
  return key;
}

}  // namespace

RobotMotionChecker::RobotMotionChecker(std::shared_ptr<const RobotBody> body,
                                       std::shared_ptr<const CollisionScene> scene,
                                       const KinematicsInterface& kinematics, JointValues state,
                                       const MotionCheckSettings& settings)
    : body_(std::move(body)),
      scene_(std::move(scene)),
      state_(std::move(state)),
      settings_(settings) {
  if (!body_ || !scene_) throw Error("motion check: no robot body or no scene");
  if (!(settings.padding > 0.0)) throw Error("motion check: the padding must be positive");
  if (!(settings.self_padding >= 0.0))
    throw Error("motion check: the padding between links must not be negative");
  if (!(settings.planning_time > 0.0) || settings.planning_checks == 0)
    throw Error("motion check: the planning budget (time and configurations) must be positive");
  const RobotModel& model = body_->model();
  const std::map<std::string, Eigen::Isometry3d> zero = model.link_poses({});
  if (const auto base = zero.find("base_link"); base != zero.end())
    T_base_root_ = base->second.inverse();
  std::map<std::string, std::string> child_of;
  for (const RobotModel::TreeJoint& j : model.tree_joints()) child_of[j.name] = j.child;
  for (const std::string& name : kinematics.groups()) {
    const std::optional<GroupInfo> g = kinematics.group(name);
    if (!g) continue;
    groups_[name] = *g;
    for (const JointInfo& j : g->joints) {
      joint_info_[j.name] = j;
      moved_by_[j.name] = body_->links_moved_by(j.name);
    }
    // The gripper: what the group's last joint moves, allowed to touch what a step means to.
    if (!g->joints.empty()) {
      const std::vector<char>& hand = moved_by_[g->joints.back().name];
      for (std::size_t i = 0; i < hand.size(); ++i)
        if (hand[i]) gripper_links_.push_back(i);
    }
  }
  // Each joint's lever: the farthest any surface point of what it moves lies from its origin, over
  // random configurations of every group's joints.
  SplitMix64 rng(settings.seed);
  for (int k = 0; k < kLeverSamples; ++k) {
    JointValues q = state_;
    for (const auto& [name, j] : joint_info_) q[name] = random_joint(j, rng);
    const std::map<std::string, Eigen::Isometry3d> poses = model.link_poses(q);
    const std::vector<Eigen::Isometry3d> placed = body_->place(q);
    for (const auto& [name, moved] : moved_by_) {
      const Eigen::Vector3d origin = poses.at(child_of.at(name)).translation();
      double& lever = lever_[name];
      for (std::size_t i = 0; i < placed.size(); ++i) {
        const BodySolid& s = body_->solids()[i];
        if (!moved[s.link]) continue;
        const double r = (placed[i].translation() - origin).norm() + s.solid.bounding_radius();
        lever = std::max(lever, kLeverMargin * r);
      }
    }
  }
}

RobotMotionChecker RobotMotionChecker::with_state(const JointValues& state) const {
  RobotMotionChecker copy(*this);
  for (const auto& [name, value] : state) copy.state_[name] = value;
  return copy;
}

double RobotMotionChecker::travel(const std::string& joint, double a, double b) const {
  const auto info = joint_info_.find(joint);
  return info == joint_info_.end() ? b - a : signed_travel(info->second, a, b);
}

double RobotMotionChecker::lever(const std::string& joint) const {
  const auto it = lever_.find(joint);
  return it == lever_.end() ? 0.0 : it->second;
}

JointValues RobotMotionChecker::merged(const JointValues& joints) const {
  JointValues q = state_;
  for (const auto& [name, value] : joints) q[name] = value;
  return q;
}

std::vector<char> RobotMotionChecker::links_moved_by(const std::vector<std::string>& joints) const {
  std::vector<char> out(body_->links().size(), 0);
  for (const std::string& j : joints) {
    const auto it = moved_by_.find(j);
    const std::vector<char> moved = it != moved_by_.end() ? it->second : body_->links_moved_by(j);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] |= moved[i];
  }
  return out;
}

std::optional<MotionContact> RobotMotionChecker::check_state(const JointValues& joints,
                                                             const std::vector<char>& moving,
                                                             const IntendedContact* intended,
                                                             double* clearance, const Needs* needs,
                                                             Needs* measured) const {
  const std::vector<Eigen::Isometry3d> placed = body_->place(merged(joints));
  std::optional<MotionContact> deepest;
  double nearest = std::numeric_limits<double>::infinity();
  const double padding = settings_.padding;
  if (measured) {
    measured->scene.assign(moving.size(), std::numeric_limits<double>::infinity());
    measured->self.assign(moving.size(), std::numeric_limits<double>::infinity());
  }
  for (std::size_t link = 0; link < moving.size(); ++link) {
    if (!moving[link]) continue;
    const double need = needs ? needs->scene[link] : padding;
    // The whole link against the grid first: most links are far from everything.
    const double bound = scene_->lower_bound(T_base_root_ * body_->link_centre(link, placed),
                                             body_->link_radius(link));
    double link_nearest = bound;
    if (bound < padding) {
      const bool hand =
          std::find(gripper_links_.begin(), gripper_links_.end(), link) != gripper_links_.end();
      link_nearest = std::numeric_limits<double>::infinity();
      for (std::size_t i : body_->link_solids(link)) {
        const BodySolid& s = body_->solids()[i];
        const SceneDistance d = scene_->distance(s.solid, T_base_root_ * placed[i], s.surface,
                                                 padding, hand ? intended : nullptr);
        link_nearest = std::min(link_nearest, d.distance);
        if (d.distance < need && (!deepest || d.distance < deepest->distance)) {
          deepest = MotionContact{body_->links()[link],
                                  d.unseen   ? "space no camera has seen"
                                  : d.hidden ? "space the sensor could not see"
                                             : "the scene",
                                  d.distance, d.where, 0.0};
        }
      }
    }
    nearest = std::min(nearest, link_nearest);
    if (measured) measured->scene[link] = link_nearest;
  }
  if (settings_.self_collisions) {
    std::optional<MotionContact> self =
        body_->self_contact(placed, moving, settings_.self_padding, needs ? &needs->self : nullptr,
                            measured ? &measured->self : nullptr);
    if (self) {
      self->where = T_base_root_ * self->where;
      nearest = std::min(nearest, self->distance);
      if (!deepest || self->distance < deepest->distance) deepest = self;
    }
  }
  if (clearance) *clearance = nearest;
  return deepest;
}

RobotMotionChecker::Needs RobotMotionChecker::needs_at(const Needs& ends_allow,
                                                       double from_end) const {
  if (from_end < kEndZone) return touching_only();
  // What an end allows holds near it only: past the end zone every centimetre of travel asks a
  // centimetre more, up to the paddings. A link that starts beside a grasped bowl may not graze a
  // shelf's roof half-way out.
  const double more = from_end - kEndZone;
  Needs needs = ends_allow;
  for (double& n : needs.scene) n = std::min(settings_.padding, n + more);
  for (double& n : needs.self) n = std::min(settings_.self_padding, n + more);
  return needs;
}

RobotMotionChecker::Needs RobotMotionChecker::touching_only() const {
  Needs none;
  none.scene.assign(body_->links().size(), 0.0);
  none.self.assign(body_->links().size(), 0.0);
  return none;
}

double RobotMotionChecker::sweep(const JointValues& a, const JointValues& b) const {
  double total = 0.0;
  for (const auto& [name, value] : b) {
    const auto from = a.find(name);
    if (from == a.end()) continue;
    total += std::abs(travel(name, from->second, value)) * lever(name);
  }
  return total;
}

std::optional<MotionContact> RobotMotionChecker::check_pose(const JointValues& joints,
                                                            const IntendedContact& intended) const {
  std::vector<std::string> names;
  for (const auto& [name, value] : joints) names.push_back(name);
  const Needs none = touching_only();
  return check_state(joints, links_moved_by(names), &intended, nullptr, &none);
}

RobotMotionChecker::Needs RobotMotionChecker::needs_between(const JointValues& from,
                                                            const JointValues& to,
                                                            const std::vector<char>& moving,
                                                            const IntendedContact* intended) const {
  Needs at_from, at_to;
  check_state(from, moving, intended, nullptr, nullptr, &at_from);
  check_state(to, moving, intended, nullptr, nullptr, &at_to);
  Needs needs;
  const auto need = [](double padding, double a, double b) {
    return std::max(0.0, std::min(padding, kEndClearanceShare * std::min(a, b)));
  };
  for (std::size_t l = 0; l < moving.size(); ++l) {
    needs.scene.push_back(need(settings_.padding, at_from.scene[l], at_to.scene[l]));
    needs.self.push_back(need(settings_.self_padding, at_from.self[l], at_to.self[l]));
  }
  return needs;
}

MotionVerdict RobotMotionChecker::check_line(const JointValues& from, const JointValues& to,
                                             const IntendedContact& intended) const {
  const JointValues a = merged(from);
  std::map<std::string, double> delta;
  double span = 0.0;  // how far any point can move along the line, m
  for (const auto& [name, value] : to) {
    const double d = travel(name, a.at(name), value);
    if (d == 0.0) continue;
    delta[name] = d;
    span += std::abs(d) * lever(name);
  }
  std::vector<std::string> names;
  for (const auto& [name, d] : delta) names.push_back(name);
  const std::vector<char> moving = links_moved_by(names);
  const int steps = std::max(1, static_cast<int>(std::ceil(span / settings_.padding)));
  JointValues b = a;
  for (const auto& [name, d] : delta) b[name] = a.at(name) + d;
  const Needs needs = needs_between(a, b, moving, &intended);
  MotionVerdict verdict;
  verdict.clearance = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    JointValues q = a;
    for (const auto& [name, d] : delta) q[name] = a.at(name) + t * d;
    double clearance = 0.0;
    const Needs here = needs_at(needs, std::min(t, 1.0 - t) * span);
    std::optional<MotionContact> contact = check_state(q, moving, &intended, &clearance, &here);
    ++verdict.samples;
    verdict.clearance = std::min(verdict.clearance, clearance);
    if (contact) {
      contact->at = t;
      verdict.contact = std::move(contact);
      break;
    }
  }
  return verdict;
}

std::vector<Eigen::Vector3d> RobotMotionChecker::unseen_along(
    const std::vector<JointValues>& path) const {
  std::vector<Eigen::Vector3d> out;
  if (path.empty()) return out;
  std::vector<std::string> names;
  for (const auto& [name, value] : path.front()) names.push_back(name);
  const std::vector<char> moving = links_moved_by(names);
  // The cubes already judged: each by the first point of the arm in it (judging every point, a
  // cube the view's edge cuts would be caught too, at twice the time of a plan).
  std::unordered_set<std::uint64_t> cells;
  const auto visit = [&](const JointValues& q) {
    const std::vector<Eigen::Isometry3d> placed = body_->place(q);
    for (std::size_t link = 0; link < moving.size(); ++link) {
      if (!moving[link]) continue;
      for (std::size_t i : body_->link_solids(link)) {
        const Eigen::Isometry3d T_base_solid = T_base_root_ * placed[i];
        for (const Eigen::Vector3d& s : body_->solids()[i].surface) {
          const Eigen::Vector3d p = T_base_solid * s;
          if (cells.insert(cell_key(p)).second && scene_->unseen(p)) out.push_back(p);
        }
      }
    }
  };
  JointValues a = merged(path.front());
  visit(a);
  for (std::size_t k = 1; k < path.size(); ++k) {
    std::map<std::string, double> delta;
    for (const auto& [name, value] : path[k]) delta[name] = travel(name, a.at(name), value);
    JointValues b = a;
    for (const auto& [name, d] : delta) b[name] = a.at(name) + d;
    const int steps = std::max(1, static_cast<int>(std::ceil(sweep(a, b) / kUnseenCell)));
    for (int j = 1; j <= steps; ++j) {
      JointValues q = a;
      for (const auto& [name, d] : delta) q[name] = a.at(name) + d * j / steps;
      visit(q);
    }
    a = b;
  }
  return out;
}

MotionPlan RobotMotionChecker::plan_around(const std::string& group, const JointValues& from,
                                           const JointValues& to,
                                           const IntendedContact& intended) const {
  const Stopwatch clock;
  const auto g = groups_.find(group);
  if (g == groups_.end()) throw Error("motion check: no group named '" + group + "'");
  const std::vector<JointInfo>& joints = g->second.joints;
  const std::size_t n = joints.size();
  const JointValues start_state = merged(from);
  std::vector<double> start(n), goal(n);
  double lever_norm = 0.0;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < n; ++i) {
    start[i] = start_state.at(joints[i].name);
    const auto target = to.find(joints[i].name);
    goal[i] = target == to.end() ? start[i]
                                 : start[i] + signed_travel(joints[i], start[i], target->second);
    lever_norm += lever(joints[i].name) * lever(joints[i].name);
    names.push_back(joints[i].name);
  }
  lever_norm = std::sqrt(lever_norm);
  JointValues goal_state = start_state;
  for (std::size_t i = 0; i < n; ++i) goal_state[names[i]] = goal[i];
  const std::vector<char> moving = links_moved_by(names);
  const Needs needs = needs_between(start_state, goal_state, moving, &intended),
              ends = touching_only();
  MotionPlan plan;
  // An end that touches has no path: say which, and what it touches.
  for (const auto& [end, state] :
       {std::pair<const char*, const JointValues*>{"the start", &start_state},
        {"the target", &goal_state}}) {
    if (const std::optional<MotionContact> c =
            check_state(*state, moving, &intended, nullptr, &ends)) {
      plan.seconds = clock.seconds();
      plan.message = std::string("no path: ") + end + " itself touches (" + describe(*c) + ")";
      return plan;
    }
  }
  JointValues q = start_state;
  const auto free = [&](const std::vector<double>& v) {
    for (std::size_t i = 0; i < n; ++i) q[names[i]] = v[i];
    const Needs here = needs_at(needs, std::min(sweep(start_state, q), sweep(goal_state, q)));
    return !check_state(q, moving, &intended, nullptr, &here);
  };
  // Motions are checked at states no farther apart than the padding moves any point
  // (sum |dq_i| lever_i <= |dq| |lever|).
  JointSpacePlannerSettings budget;
  budget.seconds = settings_.planning_time;
  budget.checks = settings_.planning_checks;
  budget.seed = settings_.seed;
  const JointSpacePath path = plan_joint_path(
      joints, start, goal, free, settings_.padding / std::max(lever_norm, 1e-9), budget);
  plan.checks = path.checks;
  plan.seconds = clock.seconds();
  if (!path.found) {
    plan.message = path.why;
    return plan;
  }
  plan.waypoints = path.waypoints;
  plan.found = true;
  return plan;
}

}  // namespace lmk
