// SPDX-License-Identifier: BSD-3-Clause
// One cluster's coarse alignment (search/fast/coarse_fit.h): the stop test after the first steps
// ends a hopeless cluster there, and a cluster that passes it ends where one uninterrupted ICP of
// all the steps would.

#include "lmk/search/fast/coarse_fit.h"

#include <gtest/gtest.h>

#include "lmk/geometry/pose.h"
#include "lmk/occupancy/distance_field.h"
#include "tests/registration/registration_fixture.h"

namespace lmk::detail {
namespace {

struct CornerScene {
  CornerScene() : target(test::corner_with_bump()), field(target.points, {0.005, 0.05}) {
    for (const auto& p : target.points) source.push_back(test::small_motion().cast<float>() * p);
    settings.termination.max_iterations = 8;
    settings.termination.translation_tolerance = 1e-9;  // every step is taken
    settings.termination.rotation_tolerance = 1e-9;
    settings.measure_final = false;
  }
  PointCloud target;
  DistanceField field;
  std::vector<Eigen::Vector3f> source;
  IcpSettings settings;
};

// A score that counts its calls and answers `value`.
CoarseScore constant_score(double value, int* calls) {
  return [value, calls](const Eigen::Isometry3f&) {
    ++*calls;
    return value;
  };
}

void expect_same_pose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double tolerance) {
  EXPECT_LE((a.translation() - b.translation()).norm(), tolerance);
  EXPECT_LE(rotation_angle_between(a.linear(), b.linear()), tolerance);
}

TEST(CoarseFit, AHopelessClusterStopsAfterTheFirstSteps) {
  const CornerScene s;
  const DistanceFieldTarget target(s.field, &s.target.normals);
  int score_calls = 0, test_calls = 0;
  const CoarseFit fit =
      coarse_fit(s.source, target, Eigen::Isometry3d::Identity(), s.settings,
                 constant_score(0.0, &score_calls), constant_score(1.0, &test_calls), 0.5);
  EXPECT_TRUE(fit.stopped);
  EXPECT_EQ(fit.iterations, kFirstCoarseSteps);
  EXPECT_DOUBLE_EQ(fit.score, 1.0);  // the test's score: the prune drops it as hopeless
  EXPECT_EQ(test_calls, 1);
  EXPECT_EQ(score_calls, 0);  // the full score is spared
  IcpSettings first = s.settings;
  first.termination.max_iterations = kFirstCoarseSteps;
  const IcpResult r = icp(s.source, target, Eigen::Isometry3d::Identity(), first);
  expect_same_pose(fit.pose, r.T_target_source, 1e-12);
}

TEST(CoarseFit, AClusterThatPassesTheTestEndsWhereOneIcpWould) {
  const CornerScene s;
  const DistanceFieldTarget target(s.field, &s.target.normals);
  int score_calls = 0, test_calls = 0;
  const CoarseFit fit =
      coarse_fit(s.source, target, Eigen::Isometry3d::Identity(), s.settings,
                 constant_score(0.25, &score_calls), constant_score(0.5, &test_calls), 0.5);
  EXPECT_FALSE(fit.stopped);
  EXPECT_DOUBLE_EQ(fit.score, 0.25);  // scored with the full score at the end
  EXPECT_EQ(test_calls, 1);
  EXPECT_EQ(score_calls, 1);
  const IcpResult whole = icp(s.source, target, Eigen::Isometry3d::Identity(), s.settings);
  EXPECT_EQ(fit.iterations, whole.iterations);
  EXPECT_EQ(fit.iterations, s.settings.termination.max_iterations);
  // The two calls differ only by the re-orthonormalisation between them.
  expect_same_pose(fit.pose, whole.T_target_source, 1e-9);
  // And the motion is recovered, as the whole ICP recovers it.
  expect_same_pose(fit.pose, test::small_motion().inverse(), 2e-3);
}

TEST(CoarseFit, WithoutAScoreEveryStepIsTakenInOneIcp) {
  const CornerScene s;
  const DistanceFieldTarget target(s.field, &s.target.normals);
  const CoarseFit fit =
      coarse_fit(s.source, target, Eigen::Isometry3d::Identity(), s.settings, {}, {}, 0.0);
  const IcpResult whole = icp(s.source, target, Eigen::Isometry3d::Identity(), s.settings);
  EXPECT_FALSE(fit.stopped);
  EXPECT_EQ(fit.iterations, whole.iterations);
  EXPECT_DOUBLE_EQ(fit.score, 0.0);
  expect_same_pose(fit.pose, whole.T_target_source, 0.0);
}

TEST(CoarseFit, WithoutATestTheScoreItselfDecides) {
  const CornerScene s;
  const DistanceFieldTarget target(s.field, &s.target.normals);
  int score_calls = 0;
  const CoarseFit fit = coarse_fit(s.source, target, Eigen::Isometry3d::Identity(), s.settings,
                                   constant_score(1.0, &score_calls), {}, 0.5);
  EXPECT_TRUE(fit.stopped);
  EXPECT_EQ(score_calls, 1);
  EXPECT_EQ(fit.iterations, kFirstCoarseSteps);
}

}  // namespace
}  // namespace lmk::detail
