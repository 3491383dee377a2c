// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/oriented_bounding_box.h"

#include <gtest/gtest.h>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/random.h"

namespace lmk {
namespace {

TEST(OrientedBoundingBox, RecoversARotatedBoxAndHoldsEveryPoint) {
  const Box truth(pose_from_xyz_rpy({0.5, -1.0, 2.0}, {0.3, 0.5, 1.2}), {0.4, 0.2, 0.1});
  SplitMix64 rng(12);
  PointCloud cloud;
  for (const auto& c : truth.corners()) cloud.points.push_back(c.cast<float>());
  for (int i = 0; i < 3000; ++i) {
    const Eigen::Vector3d u(rng.uniform01() - 0.5, rng.uniform01() - 0.5, rng.uniform01() - 0.5);
    cloud.points.push_back((truth.pose * u.cwiseProduct(truth.size)).cast<float>());
  }
  cloud.set_unorganized();
  const Box box = oriented_bounding_box(cloud);
  ASSERT_TRUE(box.is_valid());
  EXPECT_LT((box.center() - truth.center()).norm(), 1e-3);
  EXPECT_NEAR(box.volume(), truth.volume(), 0.02 * truth.volume());
  // Sides sorted by length agree, and the longest axis is parallel to the true longest axis.
  Eigen::Vector3d a = box.size, b = truth.size;
  std::sort(a.data(), a.data() + 3);
  std::sort(b.data(), b.data() + 3);
  EXPECT_LT((a - b).norm(), 2e-3);
  int longest = 0;
  box.size.maxCoeff(&longest);
  EXPECT_GT(std::abs(box.pose.linear().col(longest).dot(truth.pose.linear().col(0))), 0.999);
  // Every point inside, up to float rounding of the points.
  Box grown = box;
  grown.size.array() += 1e-5;
  for (const auto& p : cloud.points) EXPECT_TRUE(grown.contains(p));
}

TEST(OrientedBoundingBox, IsDeterministic) {
  SplitMix64 rng(3);
  PointCloud cloud;
  for (int i = 0; i < 500; ++i)
    cloud.points.emplace_back(rng.normal(), 0.5 * rng.normal(), 0.2 * rng.normal());
  cloud.set_unorganized();
  const Box a = oriented_bounding_box(cloud), b = oriented_bounding_box(cloud);
  EXPECT_TRUE(a.pose.isApprox(b.pose));
  EXPECT_EQ(a.size, b.size);
}

TEST(OrientedBoundingBox, NeedsFourFinitePoints) {
  PointCloud cloud({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {std::nanf(""), 0, 0}});
  EXPECT_THROW(oriented_bounding_box(cloud), Error);
}

}  // namespace
}  // namespace lmk
