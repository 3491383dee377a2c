// SPDX-License-Identifier: BSD-3-Clause
// The joint-space planner (pr2/joint_space_planner.h) in a plane of two joints: a path around a
// disc, passing only through free states; the same path for the same seed whatever was planned
// before; ends outside the limits or not free refused at once; a budget of configurations that
// ends a search with no way through, whatever the clock says.

#include "lmk/pr2/joint_space_planner.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lmk {
namespace {

std::vector<JointInfo> two_joints() {
  return {{"a", "revolute", -2.0, 2.0, 1.0}, {"b", "revolute", -2.0, 2.0, 1.0}};
}

// Free outside a disc of radius 0.5 at the origin.
bool outside_disc(const std::vector<double>& q) { return std::hypot(q[0], q[1]) > 0.5; }

// Only the clock's budget is generous: the tests end on configurations checked.
JointSpacePlannerSettings untimed(std::uint64_t seed = 1) {
  JointSpacePlannerSettings s;
  s.seconds = 1e6;
  s.seed = seed;
  return s;
}

TEST(JointSpacePlanner, GoesAroundADiscThroughFreeStatesOnly) {
  const std::vector<double> start = {-1.5, 0.0}, goal = {1.5, 0.0};
  const JointSpacePath path =
      plan_joint_path(two_joints(), start, goal, outside_disc, 0.01, untimed());
  ASSERT_TRUE(path.found) << path.why;
  ASSERT_FALSE(path.waypoints.empty());
  EXPECT_GT(path.checks, 0u);
  EXPECT_NEAR(path.waypoints.back()[0], 1.5, 1e-9);
  EXPECT_NEAR(path.waypoints.back()[1], 0.0, 1e-9);
  // Every segment, sampled finely, stays outside the disc.
  std::vector<double> at = start;
  for (const std::vector<double>& next : path.waypoints) {
    for (int k = 0; k <= 100; ++k) {
      const double t = k / 100.0;
      const std::vector<double> q = {at[0] + t * (next[0] - at[0]), at[1] + t * (next[1] - at[1])};
      ASSERT_TRUE(outside_disc(q)) << q[0] << ", " << q[1];
    }
    at = next;
  }
}

// The first search checks motions at five times the step (fewer checks); what it finds is checked
// at the step before it is returned. A wall 4 cm thick, which that search's 5 cm checks can step
// over, is crossed through its gap only (to within the 1 cm step at its corners).
TEST(JointSpacePlanner, AWallThinnerThanTheFirstSearchsStepIsCrossedOnlyThroughItsGap) {
  const auto wall = [](const std::vector<double>& q) {
    return std::abs(q[0]) > 0.02 || (q[1] > 1.5 && q[1] < 1.8);
  };
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const std::vector<double> start = {-1.0, 0.0}, goal = {1.0, 0.0};
    const JointSpacePath path =
        plan_joint_path(two_joints(), start, goal, wall, 0.01, untimed(seed));
    ASSERT_TRUE(path.found) << path.why;
    int crossings = 0;
    std::vector<double> at = start;
    for (const std::vector<double>& next : path.waypoints) {
      if ((at[0] < 0.0) != (next[0] < 0.0)) {
        ++crossings;
        const double t = -at[0] / (next[0] - at[0]);
        const double y = at[1] + t * (next[1] - at[1]);
        EXPECT_TRUE(y > 1.49 && y < 1.81) << "seed " << seed << ": crossed at " << y;
      }
      at = next;
    }
    EXPECT_GE(crossings, 1) << "seed " << seed;
  }
}

TEST(JointSpacePlanner, TheSameSeedGivesTheSamePathWhateverWasPlannedBefore) {
  const std::vector<double> start = {-1.5, 0.2}, goal = {1.5, -0.2};
  const JointSpacePath first =
      plan_joint_path(two_joints(), start, goal, outside_disc, 0.01, untimed(7));
  plan_joint_path(two_joints(), {-1.0, -1.0}, {1.0, 1.0}, outside_disc, 0.01, untimed(8));
  const JointSpacePath again =
      plan_joint_path(two_joints(), start, goal, outside_disc, 0.01, untimed(7));
  ASSERT_TRUE(first.found && again.found);
  EXPECT_EQ(first.checks, again.checks);
  EXPECT_EQ(first.waypoints, again.waypoints);
}

TEST(JointSpacePlanner, EndsOutsideTheLimitsOrNotFreeAreRefusedAtOnce) {
  const JointSpacePath outside =
      plan_joint_path(two_joints(), {-1.5, 0.0}, {2.5, 0.0}, outside_disc, 0.01, untimed());
  EXPECT_FALSE(outside.found);
  EXPECT_EQ(outside.why, "no path: the goal is outside a's limits");
  EXPECT_EQ(outside.checks, 0u);
  const JointSpacePath inside =
      plan_joint_path(two_joints(), {0.1, 0.1}, {1.5, 0.0}, outside_disc, 0.01, untimed());
  EXPECT_FALSE(inside.found);
  EXPECT_EQ(inside.why, "no path: the start is not free");
  EXPECT_EQ(inside.checks, 1u);
  // A rounding past a limit (start + (goal - start) != goal) is on the limit.
  const JointSpacePath on_limit =
      plan_joint_path(two_joints(), {-1.5, 0.0}, {2.0 + 1e-12, 0.0}, outside_disc, 0.01, untimed());
  ASSERT_TRUE(on_limit.found) << on_limit.why;
  EXPECT_EQ(on_limit.waypoints.back()[0], 2.0);
}

TEST(JointSpacePlanner, ABudgetOfConfigurationsEndsASearchWithNoWayThrough) {
  // A wall across the whole plane at a = 0: nothing joins the two sides.
  const auto walled = [](const std::vector<double>& q) { return std::abs(q[0]) > 0.1; };
  JointSpacePlannerSettings settings = untimed();
  settings.checks = 500;
  const JointSpacePath path =
      plan_joint_path(two_joints(), {-1.5, 0.0}, {1.5, 0.0}, walled, 0.01, settings);
  EXPECT_FALSE(path.found);
  EXPECT_GE(path.checks, 500u);
  EXPECT_EQ(path.why, "no collision-free path within 500 configurations checked");
}

}  // namespace
}  // namespace lmk
