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

// A corner with a bump (every motion is fixed by it), its distance field, and the corner moved a
// little as the source; ICP takes every step it is allowed.
class CoarseFitTest : public ::testing::Test {
 protected:
  CoarseFitTest()
      : corner_(test::corner_with_bump()),
        field_(corner_.points, {0.005, 0.05}),
        target_(field_, &corner_.normals) {
    for (const auto& p : corner_.points) source_.push_back(test::small_motion().cast<float>() * p);
    settings_.termination.max_iterations = 8;
    settings_.termination.translation_tolerance = 1e-9;
    settings_.termination.rotation_tolerance = 1e-9;
    settings_.measure_final = false;
  }

  // coarse_fit from the identity with scores that answer `score` and `test` (none where
  // negative), counting their calls.
  CoarseFit fit(double score, double test, double hopeless_above) {
    const auto counted = [](double value, int* calls) -> CoarseScore {
      if (value < 0.0) return {};
      return [value, calls](const Eigen::Isometry3f&) {
        ++*calls;
        return value;
      };
    };
    return coarse_fit(source_, target_, Eigen::Isometry3d::Identity(), settings_,
                      counted(score, &score_calls_), counted(test, &test_calls_), hopeless_above);
  }

  // One uninterrupted ICP of `steps` steps from the identity.
  IcpResult icp_of(int steps) const {
    IcpSettings s = settings_;
    s.termination.max_iterations = steps;
    return icp(source_, target_, Eigen::Isometry3d::Identity(), s);
  }

  PointCloud corner_;
  DistanceField field_;
  DistanceFieldTarget target_;
  std::vector<Eigen::Vector3f> source_;
  IcpSettings settings_;
  int score_calls_ = 0, test_calls_ = 0;
};

void expect_same_pose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double tolerance) {
  EXPECT_LE((a.translation() - b.translation()).norm(), tolerance);
  EXPECT_LE(rotation_angle_between(a.linear(), b.linear()), tolerance);
}

TEST_F(CoarseFitTest, AHopelessClusterStopsAfterTheFirstSteps) {
  const CoarseFit f = fit(0.0, 1.0, 0.5);
  EXPECT_TRUE(f.stopped);
  EXPECT_EQ(f.iterations, kFirstCoarseSteps);
  EXPECT_DOUBLE_EQ(f.score, 1.0);  // the test's score: the prune drops it as hopeless
  EXPECT_EQ(test_calls_, 1);
  EXPECT_EQ(score_calls_, 0);  // the full score is spared
  expect_same_pose(f.pose, icp_of(kFirstCoarseSteps).T_target_source, 1e-12);
}

TEST_F(CoarseFitTest, AClusterThatPassesTheTestEndsWhereOneIcpWould) {
  const CoarseFit f = fit(0.25, 0.5, 0.5);
  EXPECT_FALSE(f.stopped);
  EXPECT_DOUBLE_EQ(f.score, 0.25);  // scored with the full score at the end
  EXPECT_EQ(test_calls_, 1);
  EXPECT_EQ(score_calls_, 1);
  const IcpResult whole = icp_of(settings_.termination.max_iterations);
  EXPECT_EQ(f.iterations, whole.iterations);
  EXPECT_EQ(f.iterations, settings_.termination.max_iterations);
  // The two calls differ only by the re-orthonormalisation between them.
  expect_same_pose(f.pose, whole.T_target_source, 1e-9);
  // And the motion is recovered, as the whole ICP recovers it.
  expect_same_pose(f.pose, test::small_motion().inverse(), 2e-3);
}

TEST_F(CoarseFitTest, WithoutAScoreEveryStepIsTakenInOneIcp) {
  const CoarseFit f = fit(-1.0, -1.0, 0.0);
  const IcpResult whole = icp_of(settings_.termination.max_iterations);
  EXPECT_FALSE(f.stopped);
  EXPECT_EQ(f.iterations, whole.iterations);
  EXPECT_DOUBLE_EQ(f.score, 0.0);
  expect_same_pose(f.pose, whole.T_target_source, 0.0);
}

TEST_F(CoarseFitTest, WithoutATestTheScoreItselfDecides) {
  const CoarseFit f = fit(1.0, -1.0, 0.5);
  EXPECT_TRUE(f.stopped);
  EXPECT_EQ(score_calls_, 1);
  EXPECT_EQ(f.iterations, kFirstCoarseSteps);
}

}  // namespace
}  // namespace lmk::detail
