// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pr2/robot_motion_checker.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "lmk/geometry/error.h"
#include "lmk/geometry/random.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/pbd/joint_motion.h"

namespace lmk {

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

constexpr int kLeverSamples = 64;  // random configurations the levers are bounded over
constexpr double kLeverMargin = 1.1;
// A link near something at either end of a motion must keep this share of that distance on the way.
constexpr double kEndClearanceShare = 0.5;
// Within this much travel of either end (m, the farthest any point moved), a link need only stay
// out of things: it leaves a grasp, or arrives at one, within the padding by design.
constexpr double kEndZone = 0.05;
// The path is shortened and smoothed for at most this share of the time its search took, plus a
// floor: a path found fast is simplified fast.
constexpr double kSmoothingShare = 0.5;
constexpr double kSmoothingFloor = 0.05;  // s

// OMPL's random numbers are seeded once per process, before the first planner draws any.
void seed_planner_once(std::uint64_t seed) {
  static std::once_flag once;
  std::call_once(once, [seed] {
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
    ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(seed));
  });
}

// The group's joint space for the planner: each joint within its limits, a continuous one a half
// turn beyond either end of the motion.
std::shared_ptr<ob::RealVectorStateSpace> joint_space(const std::vector<JointInfo>& joints,
                                                      const std::vector<double>& start,
                                                      const std::vector<double>& goal) {
  const unsigned n = static_cast<unsigned>(joints.size());
  auto space = std::make_shared<ob::RealVectorStateSpace>(n);
  ob::RealVectorBounds bounds(n);
  for (unsigned i = 0; i < n; ++i) {
    const JointInfo& j = joints[i];
    bounds.setLow(i, j.continuous() ? std::min(start[i], goal[i]) - M_PI : j.lower);
    bounds.setHigh(i, j.continuous() ? std::max(start[i], goal[i]) + M_PI : j.upper);
  }
  space->setBounds(bounds);
  return space;
}

// The path's states after its start, as joint vectors within the joints' limits: the smoothing's
// interpolated states may round a hair past a limit the path runs along.
std::vector<std::vector<double>> waypoints_of(const og::PathGeometric& path,
                                              const std::vector<JointInfo>& joints) {
  std::vector<std::vector<double>> out;
  for (std::size_t k = 1; k < path.getStateCount(); ++k) {
    const auto* v = path.getState(k)->as<ob::RealVectorStateSpace::StateType>();
    std::vector<double> q(joints.size());
    for (std::size_t i = 0; i < joints.size(); ++i) {
      q[i] = (*v)[i];
      if (!joints[i].continuous()) q[i] = std::clamp(q[i], joints[i].lower, joints[i].upper);
    }
    out.push_back(std::move(q));
  }
  return out;
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
  if (!(settings.planning_time > 0.0))
    throw Error("motion check: the planning time must be positive");
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
                                  d.hidden ? "space the sensor could not see" : "the scene",
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
  const Needs needs = needs_between(a, b, moving, &intended), ends = touching_only();
  MotionVerdict verdict;
  verdict.clearance = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    JointValues q = a;
    for (const auto& [name, d] : delta) q[name] = a.at(name) + t * d;
    double clearance = 0.0;
    const bool near_end = std::min(t, 1.0 - t) * span < kEndZone;
    std::optional<MotionContact> contact =
        check_state(q, moving, &intended, &clearance, near_end ? &ends : &needs);
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
  seed_planner_once(settings_.seed);
  const auto space = joint_space(joints, start, goal);
  og::SimpleSetup setup(space);
  const std::vector<char> moving = links_moved_by(names);
  const auto values_of = [&](const ob::State* s) {
    JointValues q = start_state;
    const auto* v = s->as<ob::RealVectorStateSpace::StateType>();
    for (std::size_t i = 0; i < n; ++i) q[names[i]] = (*v)[i];
    return q;
  };
  JointValues goal_state = start_state;
  for (std::size_t i = 0; i < n; ++i) goal_state[names[i]] = goal[i];
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
  setup.setStateValidityChecker([&](const ob::State* s) {
    if (!space->satisfiesBounds(s)) return false;
    const JointValues q = values_of(s);
    const bool near_end = std::min(sweep(start_state, q), sweep(goal_state, q)) < kEndZone;
    return !check_state(q, moving, &intended, nullptr, near_end ? &ends : &needs);
  });
  // Motions are checked at states no farther apart than the padding moves any point
  // (sum |dq_i| lever_i <= |dq| |lever|).
  setup.getSpaceInformation()->setStateValidityCheckingResolution(
      std::min(0.05, settings_.padding / std::max(lever_norm, 1e-9) / space->getMaximumExtent()));
  ob::ScopedState<> s0(space), s1(space);
  for (std::size_t i = 0; i < n; ++i) s0[i] = start[i], s1[i] = goal[i];
  setup.setStartAndGoalStates(s0, s1);
  setup.setPlanner(std::make_shared<og::RRTConnect>(setup.getSpaceInformation()));
  char budget[64];
  std::snprintf(budget, sizeof(budget), "%.3g s", settings_.planning_time);
  const ob::PlannerStatus status = setup.solve(settings_.planning_time);
  if (status != ob::PlannerStatus::EXACT_SOLUTION) {
    plan.seconds = clock.seconds();
    plan.message = std::string("no collision-free path within ") + budget;
    return plan;
  }
  const double solved = clock.seconds();
  setup.simplifySolution(std::min(kSmoothingShare * solved + kSmoothingFloor,
                                  std::max(0.0, settings_.planning_time - solved)));
  plan.waypoints = waypoints_of(setup.getSolutionPath(), joints);
  plan.found = true;
  plan.seconds = clock.seconds();
  return plan;
}

}  // namespace lmk
