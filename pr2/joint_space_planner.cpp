// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pr2/joint_space_planner.h"

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>

#include "lmk/geometry/error.h"
#include "lmk/geometry/random.h"

namespace lmk {

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

constexpr double kLimitRounding = 1e-9;  // rad or m
// The first search's motion-check step, in the caller's steps (plan_joint_path).
constexpr double kCoarse = 5.0;

// OMPL draws each generator's seed from one process-wide sequence, so a plan would depend on every
// plan made before it (and on threads' order). Each piece below reseeds its own generator from
// the plan's seed instead.
std::uint_fast32_t local_seed(std::uint64_t seed, std::uint64_t stream) {
  SplitMix64 mix(seed * 0x9E3779B97F4A7C15ull + stream);
  return static_cast<std::uint_fast32_t>(mix.next() & 0xFFFFFFFFu);
}

class SeededSampler : public ob::RealVectorStateSampler {
 public:
  SeededSampler(const ob::StateSpace* space, std::uint_fast32_t seed)
      : ob::RealVectorStateSampler(space) {
    rng_.setLocalSeed(seed);
  }
};

class SeededRRTConnect : public og::RRTConnect {
 public:
  SeededRRTConnect(const ob::SpaceInformationPtr& si, std::uint_fast32_t seed)
      : og::RRTConnect(si) {
    rng_.setLocalSeed(seed);
  }
};

class SeededSimplifier : public og::PathSimplifier {
 public:
  SeededSimplifier(const ob::SpaceInformationPtr& si, const ob::GoalPtr& goal,
                   std::uint_fast32_t seed)
      : og::PathSimplifier(si, goal) {
    rng_.setLocalSeed(seed);
  }
};

void quiet_ompl_once() {
  static std::once_flag once;
  std::call_once(once, [] { ompl::msg::setLogLevel(ompl::msg::LOG_NONE); });
}

// The joints' box: each within its limits, a continuous one a half turn beyond either end.
std::shared_ptr<ob::RealVectorStateSpace> joint_space(const std::vector<JointInfo>& joints,
                                                      const std::vector<double>& start,
                                                      const std::vector<double>& goal,
                                                      std::uint64_t seed) {
  const unsigned n = static_cast<unsigned>(joints.size());
  auto space = std::make_shared<ob::RealVectorStateSpace>(n);
  ob::RealVectorBounds bounds(n);
  for (unsigned i = 0; i < n; ++i) {
    const JointInfo& j = joints[i];
    bounds.setLow(i, j.continuous() ? std::min(start[i], goal[i]) - M_PI : j.lower);
    bounds.setHigh(i, j.continuous() ? std::max(start[i], goal[i]) + M_PI : j.upper);
  }
  space->setBounds(bounds);
  auto samplers = std::make_shared<std::uint64_t>(0);
  space->setStateSamplerAllocator([seed, samplers](const ob::StateSpace* s) {
    return std::make_shared<SeededSampler>(s, local_seed(seed, 16 + (*samplers)++));
  });
  return space;
}

// The path's states after its start, within the joints' limits: the smoothing's interpolated
// states may round a hair past a limit the path runs along.
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

void check_inputs(const std::vector<JointInfo>& joints, const std::vector<double>& start,
                  const std::vector<double>& goal, double max_step,
                  const JointSpacePlannerSettings& settings) {
  if (joints.empty() || start.size() != joints.size() || goal.size() != joints.size())
    throw Error("joint-space planner: the start and the goal must give every joint");
  if (!(max_step > 0.0)) throw Error("joint-space planner: the check step must be positive");
  if (!(settings.seconds > 0.0) || settings.checks == 0)
    throw Error("joint-space planner: the budget (seconds and configurations) must be positive");
}

// Either end outside the limits: the search would wait for it until the clock ran out, whatever
// its budget of configurations. An end a rounding past a limit (a + (b - a) != b) is put on it.
// Returns why not, or "".
std::string clamp_ends(const std::vector<JointInfo>& joints, std::vector<double>& start,
                       std::vector<double>& goal) {
  for (const auto& [end, q] :
       {std::pair<const char*, std::vector<double>*>{"start", &start}, {"goal", &goal}}) {
    for (std::size_t i = 0; i < joints.size(); ++i) {
      if (joints[i].continuous()) continue;
      double& v = (*q)[i];
      if (v < joints[i].lower - kLimitRounding || v > joints[i].upper + kLimitRounding)
        return std::string("no path: the ") + end + " is outside " + joints[i].name + "'s limits";
      v = std::clamp(v, joints[i].lower, joints[i].upper);
    }
  }
  return "";
}

// Checks each motion of `waypoints` (after `start`) at states no farther apart than `step`, the
// waypoints themselves already checked; counts the checks.
bool path_free(const std::vector<double>& start, const std::vector<std::vector<double>>& waypoints,
               const std::function<bool(const std::vector<double>&)>& free, double step,
               std::size_t& checks) {
  const std::vector<double>* a = &start;
  std::vector<double> q(start.size());
  for (const std::vector<double>& b : waypoints) {
    double length = 0.0;
    for (std::size_t i = 0; i < q.size(); ++i) length += ((*a)[i] - b[i]) * ((*a)[i] - b[i]);
    const int pieces = static_cast<int>(std::ceil(std::sqrt(length) / step));
    for (int k = 1; k < pieces; ++k) {
      const double t = static_cast<double>(k) / pieces;
      for (std::size_t i = 0; i < q.size(); ++i) q[i] = (*a)[i] + t * (b[i] - (*a)[i]);
      ++checks;
      if (!free(q)) return false;
    }
    a = &b;
  }
  return true;
}

// RRT-Connect from `start` to `goal` with motions checked at states `step` apart, then shortened
// and smoothed with a share of what the search took (a path found fast is simplified fast), all
// within `deadline` and the settings' configurations (`checks` counts them). Fills `waypoints`,
// or returns why not.
std::string search(const std::vector<JointInfo>& joints, const std::vector<double>& start,
                   const std::vector<double>& goal,
                   const std::function<bool(const std::vector<double>&)>& free, double step,
                   const JointSpacePlannerSettings& settings,
                   const ob::PlannerTerminationCondition& deadline, std::size_t& checks,
                   std::vector<std::vector<double>>& waypoints) {
  const auto space = joint_space(joints, start, goal, settings.seed);
  og::SimpleSetup setup(space);
  const std::size_t n = joints.size();
  std::vector<double> q(n);
  setup.setStateValidityChecker([&](const ob::State* s) {
    ++checks;
    if (!space->satisfiesBounds(s)) return false;
    const auto* v = s->as<ob::RealVectorStateSpace::StateType>();
    for (std::size_t i = 0; i < n; ++i) q[i] = (*v)[i];
    return free(q);
  });
  const ob::SpaceInformationPtr si = setup.getSpaceInformation();
  si->setStateValidityCheckingResolution(std::min(0.05, step / space->getMaximumExtent()));
  ob::ScopedState<> s0(space), s1(space);
  for (std::size_t i = 0; i < n; ++i) s0[i] = start[i], s1[i] = goal[i];
  setup.setStartAndGoalStates(s0, s1);
  setup.setPlanner(std::make_shared<SeededRRTConnect>(si, local_seed(settings.seed, 1)));
  setup.setup();
  const auto spent = [&](std::size_t limit) {
    return ob::plannerOrTerminationCondition(
        deadline, ob::PlannerTerminationCondition([&checks, limit] { return checks >= limit; }));
  };
  const std::size_t before = checks;
  const ob::PlannerStatus status = setup.getPlanner()->solve(spent(settings.checks));
  if (status != ob::PlannerStatus::EXACT_SOLUTION) {
    char budget[96];
    if (checks >= settings.checks)
      std::snprintf(budget, sizeof(budget), "%zu configuration%s checked", settings.checks,
                    settings.checks == 1 ? "" : "s");
    else
      std::snprintf(budget, sizeof(budget), "%.3g s", settings.seconds);
    return std::string("no collision-free path within ") + budget;
  }
  auto* found = setup.getProblemDefinition()->getSolutionPath()->as<og::PathGeometric>();
  const std::size_t smoothing =
      std::max(settings.smoothing_floor,
               static_cast<std::size_t>(settings.smoothing_share * (checks - before)));
  SeededSimplifier simplifier(si, setup.getProblemDefinition()->getGoal(),
                              local_seed(settings.seed, 2));
  simplifier.simplify(*found, spent(std::min(settings.checks, checks + smoothing)));
  waypoints = waypoints_of(*found, joints);
  return "";
}

}  // namespace

JointSpacePath plan_joint_path(const std::vector<JointInfo>& joints,
                               const std::vector<double>& start, const std::vector<double>& goal,
                               const std::function<bool(const std::vector<double>&)>& free,
                               double max_step, const JointSpacePlannerSettings& settings) {
  check_inputs(joints, start, goal, max_step, settings);
  JointSpacePath path;
  std::vector<double> start_in(start), goal_in(goal);
  path.why = clamp_ends(joints, start_in, goal_in);
  if (!path.why.empty()) return path;
  std::size_t checks = 0;
  for (const auto& [end, q_end] :
       {std::pair<const char*, const std::vector<double>*>{"start", &start_in},
        {"goal", &goal_in}}) {
    ++checks;
    if (!free(*q_end)) {
      path.checks = checks;
      path.why = std::string("no path: the ") + end + " is not free";
      return path;
    }
  }
  quiet_ompl_once();
  const auto deadline = ob::timedPlannerTerminationCondition(settings.seconds);
  // First with motions checked at kCoarse times the step, the path found then checked at the
  // step itself: most of a search's checks are on motions it then drops. A path that fails at
  // the step is searched for again at the step, within what is left of the budget. A coarse
  // search out of budget ends it: the fine one would have no more of it.
  path.why = search(joints, start_in, goal_in, free, kCoarse * max_step, settings, deadline, checks,
                    path.waypoints);
  if (path.why.empty() && !path_free(start_in, path.waypoints, free, max_step, checks)) {
    path.waypoints.clear();
    path.why = search(joints, start_in, goal_in, free, max_step, settings, deadline, checks,
                      path.waypoints);
  }
  path.found = path.why.empty();
  path.checks = checks;
  return path;
}

}  // namespace lmk
