// SPDX-License-Identifier: BSD-3-Clause
// The distance field against brute-force nearest-point distances, and its band behaviour.

#include "lmk/occupancy/distance_field.h"

#include <gtest/gtest.h>

#include "lmk/geometry/error.h"
#include "lmk/geometry/random.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

float brute_force_distance(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& q) {
  float best = std::numeric_limits<float>::infinity();
  for (const auto& p : points) best = std::min(best, (p - q).norm());
  return best;
}

// The voxel centres of the cube reaching `half` voxels either side of the origin on each axis.
std::vector<Eigen::Vector3f> voxel_centres(int half, double voxel) {
  std::vector<Eigen::Vector3f> out;
  for (int x = -half; x <= half; ++x) {
    for (int y = -half; y <= half; ++y) {
      for (int z = -half; z <= half; ++z) {
        out.push_back(Eigen::Vector3f(x, y, z) * static_cast<float>(voxel));
      }
    }
  }
  return out;
}

TEST(DistanceField, AgreesWithBruteForceWithinHalfAVoxelInsideTheBand) {
  const PointCloud cloud = test::random_cloud(400, 7, 0.5f);  // in a 1 m cube about the origin
  const DistanceFieldSettings settings{0.02, 0.08};
  const DistanceField field(cloud.points, settings);
  const auto sampler = field.sampler();
  SplitMix64 rng(3);
  int inside_band = 0;
  for (int k = 0; k < 4000; ++k) {
    const Eigen::Vector3f q = Eigen::Vector3f(rng.uniform01(), rng.uniform01(), rng.uniform01()) -
                              Eigen::Vector3f::Constant(0.5f);
    const float truth = brute_force_distance(cloud.points, q);
    // The band is exact where every corner of the query's cell is within it too.
    if (truth > settings.band - settings.voxel_size * std::sqrt(3.0f)) continue;
    ++inside_band;
    EXPECT_NEAR(sampler.distance(q), truth, 0.5 * settings.voxel_size) << q.transpose();
  }
  EXPECT_GT(inside_band, 500);
}

TEST(DistanceField, ReadsTheBandAcrossTheBandEdge) {
  // Cells straddling the band edge mix in-band corners with voxels outside it, which must read as
  // the band, never nearer. The sampler is taken from a temporary field: it keeps the grids alive.
  const std::vector<Eigen::Vector3f> one = {{0.0f, 0.0f, 0.0f}};
  const DistanceFieldSettings settings{0.01, 0.05};
  const auto sampler = DistanceField(one, settings).sampler();
  for (const Eigen::Vector3f& direction : {Eigen::Vector3f(1, 0, 0), Eigen::Vector3f(0, -1, 0),
                                           Eigen::Vector3f(1, 1, 1).normalized()}) {
    for (float r = 0.0f; r <= 0.08f; r += 0.001f) {
      const float expected = std::min(r, float(settings.band));
      EXPECT_NEAR(sampler.distance(r * direction), expected, 0.5 * settings.voxel_size)
          << "at " << r << " m along " << direction.transpose();
    }
  }
}

TEST(DistanceField, ClosestPointIsTheNearestOneForVoxelCentres) {
  const PointCloud cloud = test::random_cloud(300, 11, 0.5f);
  const DistanceField field(cloud.points, {0.05, 0.15});
  const auto sampler = field.sampler();
  SplitMix64 rng(5);
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector3f q = ((Eigen::Vector3f(rng.uniform01(), rng.uniform01(), rng.uniform01()) -
                                Eigen::Vector3f::Constant(0.5f)) /
                               0.05f)
                                  .array()
                                  .round()
                                  .matrix() *
                              0.05f;
    const float truth = brute_force_distance(cloud.points, q);
    const int index = sampler.closest(q);
    if (truth > 0.15f) {
      EXPECT_EQ(index, -1);
      continue;
    }
    ASSERT_GE(index, 0);
    EXPECT_NEAR((cloud.points[static_cast<std::size_t>(index)] - q).norm(), truth, 1e-5);
  }
}

TEST(DistanceField, ABandWiderThanALeafNodeHoldsExactlyTheVoxelsWithinIt) {
  // A band of 12 voxels reaches across several 8-voxel leaf nodes from each point: every voxel
  // centre within the band of a point, and no other, is active, and holds its nearest point.
  const PointCloud cloud = test::random_cloud(20, 17, 0.2f);
  const double voxel = 0.01, band = 0.12;
  const DistanceField field(cloud.points, {voxel, band});
  const auto sampler = field.sampler();
  std::size_t within = 0;
  for (const Eigen::Vector3f& q : voxel_centres(35, voxel)) {
    const float truth = brute_force_distance(cloud.points, q);
    const int index = sampler.closest(q);
    if (truth > band + 1e-5) {
      ASSERT_EQ(index, -1) << q.transpose();
      continue;
    }
    if (truth > band - 1e-5) continue;  // at the band's edge itself, either way
    ++within;
    ASSERT_GE(index, 0) << q.transpose() << " is " << truth << " m from its nearest point";
    EXPECT_NEAR((cloud.points[static_cast<std::size_t>(index)] - q).norm(), truth, 1e-5);
  }
  EXPECT_GT(within, 10000u);
  EXPECT_NEAR(static_cast<double>(field.active_voxels()), static_cast<double>(within),
              0.001 * within);
}

TEST(DistanceField, PointsHalfwayBetweenVoxelCentresReachTheirWholeBand) {
  // A point at a half voxel, on either side of zero, splats from a box about its rounded voxel:
  // whichever way it rounds, every voxel within the band must be reached, on every axis.
  const double voxel = 0.25, band = 0.5;  // powers of two: the halves are exact in float
  const std::vector<Eigen::Vector3f> points = {{-0.625f, 0.125f, -1.125f},
                                               {1.375f, -0.875f, 0.625f}};
  const DistanceField field(points, {voxel, band});
  const auto sampler = field.sampler();
  std::size_t within = 0;
  for (const Eigen::Vector3f& q : voxel_centres(8, voxel)) {
    const float d0 = (points[0] - q).norm(), d1 = (points[1] - q).norm();
    const int index = sampler.closest(q);
    if (std::min(d0, d1) > band) {
      ASSERT_EQ(index, -1) << q.transpose();
      continue;
    }
    ++within;
    ASSERT_EQ(index, d1 < d0 ? 1 : 0) << q.transpose();
  }
  EXPECT_EQ(static_cast<std::size_t>(field.active_voxels()), within);
  EXPECT_GT(within, 40u);
}

TEST(DistanceField, PointsBeyondWhatVoxelsCanIndexAreRefused) {
  // 1 mm voxels index about 8 km along an axis; a wild point farther out is refused, not wrapped.
  const std::vector<Eigen::Vector3f> far = {{0.0f, 0.0f, 0.0f}, {0.0f, 2.0e4f, 0.0f}};
  try {
    DistanceField(far, {0.001, 0.004});
    FAIL() << "a point 20 km away was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("crop the cloud"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(DistanceField(far, {0.01, 0.04}));  // 1 cm voxels reach 80 km
}

TEST(DistanceField, BeyondTheBandIsTheBandValueAndGradientsPointAway) {
  const std::vector<Eigen::Vector3f> one = {{0.0f, 0.0f, 0.0f}};
  const DistanceField field(one, {0.01, 0.05});
  const auto sampler = field.sampler();
  EXPECT_FLOAT_EQ(sampler.distance({1.0f, 0.0f, 0.0f}), 0.05f);
  EXPECT_EQ(sampler.closest({1.0f, 0.0f, 0.0f}), -1);
  Eigen::Vector3f g;
  const float d = sampler.distance({0.025f, 0.0f, 0.0f}, &g);
  EXPECT_NEAR(d, 0.025f, 0.005f);
  EXPECT_GT(g.x(), 0.8f);  // moving away from the point increases the distance
  EXPECT_NEAR(g.y(), 0.0f, 0.2f);
}

TEST(DistanceField, SameGridsWhateverTheThreadCount) {
  // Points spread along x cover many slabs, built in parallel; the result must not depend on it.
  PointCloud cloud = test::random_cloud(2000, 13, 0.5f);
  for (auto& p : cloud.points) p.x() *= 5.0f;
  const DistanceField a(cloud.points, {0.01, 0.03});
  const DistanceField b(cloud.points, {0.01, 0.03});
  EXPECT_EQ(a.active_voxels(), b.active_voxels());
  const auto sa = a.sampler(), sb = b.sampler();
  SplitMix64 rng(1);
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Vector3f q(5 * rng.uniform01() - 2.5f, rng.uniform01() - 0.5f,
                            rng.uniform01() - 0.5f);
    EXPECT_EQ(sa.closest(q), sb.closest(q));
  }
}

TEST(DistanceField, BadSettingsAreErrors) {
  EXPECT_THROW(DistanceField({}, {0.0, 0.1}), Error);
  EXPECT_THROW(DistanceField({}, {0.01, 0.001}), Error);
  EXPECT_TRUE(DistanceField({}, {0.01, 0.02}).empty());
}

}  // namespace
}  // namespace lmk
