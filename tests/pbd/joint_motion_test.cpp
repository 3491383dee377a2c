// SPDX-License-Identifier: BSD-3-Clause
// A path through waypoints (pbd/joint_motion.h) keeps its times increasing and ends exactly at its
// duration, even with lines that take (almost) no time: the simulated PR2 refuses a trajectory
// whose times do not increase, and a step holds its arm at the path's end.

#include "lmk/pbd/joint_motion.h"

#include <gtest/gtest.h>

namespace lmk {
namespace {

GroupInfo two_joint_arm() {
  GroupInfo g;
  g.name = "arm";
  g.joints = {{"a", "revolute", -2.0, 2.0, 1.0}, {"b", "revolute", -2.0, 2.0, 1.0}};
  return g;
}

void expect_times_increase_to(const JointTrajectory& t, double duration) {
  ASSERT_FALSE(t.points.empty());
  double previous = 0.0;
  for (std::size_t p = 0; p < t.points.size(); ++p) {
    EXPECT_GT(t.points[p].time_from_start, previous) << "point " << p;
    previous = t.points[p].time_from_start;
  }
  EXPECT_EQ(t.points.back().time_from_start, duration);
}

TEST(JointPath, LinesThatTakeAlmostNoTimeStillEndOnTheDuration) {
  const GroupInfo arm = two_joint_arm();
  const std::vector<double> from{0.0, 0.0};
  // A long line, then two that barely move (a planner's waypoints a hair apart), then another.
  const std::vector<std::vector<double>> waypoints{
      {1.0, 0.5}, {1.0, 0.5 + 1e-9}, {1.0, 0.5 + 2e-9}, {0.2, -0.4}};
  for (double duration : {0.004, 0.3, 2.0, 17.0}) {
    SCOPED_TRACE(duration);
    const JointTrajectory t = joint_path(arm, from, waypoints, duration, 10);
    expect_times_increase_to(t, duration);
    EXPECT_EQ(t.points.back().positions, waypoints.back());
  }
}

TEST(JointPath, APathThatDoesNotMoveStillHasIncreasingTimes) {
  const GroupInfo arm = two_joint_arm();
  const std::vector<double> here{0.3, 0.3};
  const JointTrajectory t = joint_path(arm, here, {here, here}, 0.5, 6);
  expect_times_increase_to(t, 0.5);
}

TEST(JointPath, EachLinesShareFollowsItsTimeAtFullSpeed) {
  const GroupInfo arm = two_joint_arm();
  // The first line moves 1 rad, the second 1.5 rad, at 1 rad/s: two fifths and three fifths.
  const JointTrajectory t = joint_path(arm, {0.0, 0.0}, {{1.0, 0.0}, {1.0, 1.5}}, 5.0, 2);
  ASSERT_EQ(t.points.size(), 2u);
  EXPECT_NEAR(t.points[0].time_from_start, 2.0, 1e-12);
  EXPECT_EQ(t.points[1].time_from_start, 5.0);
}

}  // namespace
}  // namespace lmk
