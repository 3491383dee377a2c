// SPDX-License-Identifier: BSD-3-Clause
// ICP recovers known motions on a synthetic target, in both directions, with either target type,
// and resists outliers with a robust kernel.

#include "lmk/registration/icp.h"

#include <gtest/gtest.h>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/random.h"
#include "tests/registration/registration_fixture.h"

namespace lmk {
namespace {

// The source is the target moved by `T_source_target`; ICP from the identity must find its inverse.
std::vector<Eigen::Vector3f> moved(const PointCloud& target, const Eigen::Isometry3d& T) {
  std::vector<Eigen::Vector3f> out;
  for (const auto& p : target.points) out.push_back(T.cast<float>() * p);
  return out;
}

void expect_recovered(const IcpResult& r, const Eigen::Isometry3d& truth, double tolerance) {
  EXPECT_LT((r.T_target_source.translation() - truth.translation()).norm(), tolerance);
  EXPECT_LT(rotation_angle_between(r.T_target_source.linear(), truth.linear()), 10 * tolerance);
  EXPECT_LT(r.final_error, 1e-3);
  EXPECT_GT(r.inliers, 100u);
}

class IcpModes : public ::testing::TestWithParam<IcpMode> {};

TEST_P(IcpModes, RecoversAKnownMotionForwardAndInverse) {
  const PointCloud target = test::corner_with_bump();
  const KdTree tree(target);
  const KdTreeTarget kd(target, tree);
  IcpSettings s;
  s.mode = GetParam();
  s.termination.max_iterations = 100;
  // Point-to-point has the smaller basin of convergence on planar faces: it starts at half the
  // motion.
  const Eigen::Isometry3d T = test::small_motion(s.mode == IcpMode::point_to_point ? 0.5 : 1.0);
  const IcpResult forward = icp(moved(target, T), kd, Eigen::Isometry3d::Identity(), s);
  expect_recovered(forward, T.inverse(), 1e-3);
  const IcpResult inverse = icp(moved(target, T.inverse()), kd, Eigen::Isometry3d::Identity(), s);
  expect_recovered(inverse, T, 1e-3);
  EXPECT_TRUE(forward.converged);
}

INSTANTIATE_TEST_SUITE_P(Both, IcpModes,
                         ::testing::Values(IcpMode::point_to_point, IcpMode::point_to_plane));

TEST(Icp, DistanceFieldTargetRecoversAKnownMotion) {
  const PointCloud target = test::corner_with_bump();
  const DistanceField field(target.points, {0.005, 0.05});
  const DistanceFieldTarget grid(field, &target.normals);
  IcpSettings s;
  s.termination.max_iterations = 60;
  const Eigen::Isometry3d T = test::small_motion();
  const IcpResult r = icp(moved(target, T), grid, Eigen::Isometry3d::Identity(), s);
  EXPECT_LT((r.T_target_source.translation() - T.inverse().translation()).norm(), 2e-3);
  EXPECT_LT(rotation_angle_between(r.T_target_source.linear(), T.inverse().linear()), 0.02);
}

// ICP asks for a step's correspondences all at once; each target must answer exactly as it does
// one query at a time, beyond the band and for non-finite queries too.
TEST(Icp, LookingUpAllCorrespondencesAtOnceAnswersAsOneAtATime) {
  const PointCloud target = test::corner_with_bump();
  const DistanceField field(target.points, {0.005, 0.02});
  const DistanceFieldTarget grid(field, &target.normals);
  const KdTree tree(target);
  const KdTreeTarget exact(target, tree);
  std::vector<Eigen::Vector3f> queries = moved(target, test::small_motion());
  for (auto& q : queries) q += Eigen::Vector3f(0.01f, -0.02f, 0.015f);  // some beyond the band
  queries.push_back(Eigen::Vector3f::Constant(std::nanf("")));
  queries.push_back(Eigen::Vector3f(5.0f, 5.0f, 5.0f));
  for (const IcpTarget* t :
       {static_cast<const IcpTarget*>(&grid), static_cast<const IcpTarget*>(&exact)}) {
    std::vector<Eigen::Vector3f> points, normals;
    std::vector<char> found;
    t->nearest_all(queries, points, normals, found);
    ASSERT_EQ(found.size(), queries.size());
    std::size_t hits = 0, misses = 0;
    for (std::size_t k = 0; k < queries.size(); ++k) {
      Eigen::Vector3f p, n;
      const bool one = t->nearest(queries[k], p, n);
      ASSERT_EQ(static_cast<bool>(found[k]), one) << "query " << k;
      if (!one) {
        ++misses;
        continue;
      }
      ++hits;
      EXPECT_EQ(points[k], p);
      EXPECT_EQ(normals[k], n);
    }
    EXPECT_GT(hits, 100u);
    if (t == &grid) {
      EXPECT_GT(misses, 2u);
    }
  }
}

// The fast search skips the measuring pass: the pose, its steps and convergence must not change,
// whether the run ends by converging or at its iteration cap.
TEST(Icp, SkippingTheMeasuringPassChangesNothingButTheMeasurement) {
  const PointCloud target = test::corner_with_bump();
  const DistanceField field(target.points, {0.005, 0.05});
  const DistanceFieldTarget grid(field, &target.normals);
  const std::vector<Eigen::Vector3f> source = moved(target, test::small_motion());
  for (const int cap : {3, 60}) {
    IcpSettings measured;
    measured.termination.max_iterations = cap;
    IcpSettings unmeasured = measured;
    unmeasured.measure_final = false;
    const IcpResult a = icp(source, grid, Eigen::Isometry3d::Identity(), measured);
    const IcpResult b = icp(source, grid, Eigen::Isometry3d::Identity(), unmeasured);
    EXPECT_TRUE(a.T_target_source.isApprox(b.T_target_source, 0.0)) << "cap " << cap;
    EXPECT_EQ(a.iterations, b.iterations);
    EXPECT_EQ(a.converged, b.converged);
    EXPECT_EQ(a.converged, cap == 60);
  }
}

TEST(Icp, ARobustKernelResistsThirtyPercentOutliers) {
  const PointCloud target = test::corner_with_bump();
  const KdTree tree(target);
  const KdTreeTarget kd(target, tree);
  const Eigen::Isometry3d T = test::small_motion();
  std::vector<Eigen::Vector3f> source = moved(target, T);
  // 30% of the source: points scattered up to 5 cm off the surface, as clutter would be.
  SplitMix64 rng(9);
  const std::size_t outliers = source.size() * 3 / 10;
  for (std::size_t k = 0; k < outliers; ++k) {
    const std::size_t i = rng.uniform_index(source.size());
    source[i] +=
        Eigen::Vector3f(rng.uniform01() - 0.5f, rng.uniform01() - 0.5f, rng.uniform01() - 0.5f) *
        0.1f;
  }
  IcpSettings robust;
  robust.termination.max_iterations = 80;
  robust.correspondences.loss = {RobustKernel::tukey, 0.01};
  const IcpResult r = icp(source, kd, Eigen::Isometry3d::Identity(), robust);
  EXPECT_LT((r.T_target_source.translation() - T.inverse().translation()).norm(), 2e-3);
  EXPECT_LT(rotation_angle_between(r.T_target_source.linear(), T.inverse().linear()), 0.01);
}

TEST(Icp, BadSettingsAreErrors) {
  const PointCloud target = test::corner_with_bump();
  PointCloud bare = target;
  bare.normals.clear();
  const KdTree tree(bare);
  const KdTreeTarget no_normals(bare, tree);
  EXPECT_THROW(icp(bare.points, no_normals, Eigen::Isometry3d::Identity()), Error);  // plane
  IcpSettings s;
  s.mode = IcpMode::point_to_point;
  s.termination.max_iterations = 0;
  EXPECT_THROW(icp(bare.points, no_normals, Eigen::Isometry3d::Identity(), s), Error);
  EXPECT_THROW(robust_kernel_from_string("magic"), Error);
  EXPECT_EQ(robust_kernel_from_string("cauchy"), RobustKernel::cauchy);
}

}  // namespace
}  // namespace lmk
