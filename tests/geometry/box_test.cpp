// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/box.h"

#include <gtest/gtest.h>

#include "lmk/geometry/error.h"
#include "lmk/geometry/filters.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/random.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

Box rotated_box() {
  return Box(pose_from_xyz_rpy({0.1, -0.2, 0.3}, {0.4, -0.7, 1.1}), {0.6, 0.3, 0.9});
}

TEST(Box, ContainsItsCentreAndCornersButNotBeyond) {
  const Box box = rotated_box();
  EXPECT_TRUE(box.contains(box.center()));
  for (const Eigen::Vector3d& c : box.corners()) {
    // Corners lie on the surface; nudged towards the centre they are inside, away they are out.
    EXPECT_TRUE(box.contains((c + 1e-9 * (box.center() - c)).eval()));
    EXPECT_FALSE(box.contains((c + 1e-3 * (c - box.center())).eval()));
  }
}

TEST(Box, CornersSpanTheSizeAlongTheBoxAxes) {
  const Box box = rotated_box();
  const auto corners = box.corners();
  for (int axis = 0; axis < 3; ++axis) {
    // Corners 0 and (1 << axis) differ only along `axis`.
    const Eigen::Vector3d edge = corners[1 << axis] - corners[0];
    EXPECT_NEAR(edge.norm(), box.size[axis], 1e-12);
    EXPECT_NEAR(edge.normalized().dot(box.pose.linear().col(axis)), 1.0, 1e-12);
  }
}

TEST(Box, TransformedMapsCornersAndMembership) {
  const Box box = rotated_box();
  const Eigen::Isometry3d T = pose_from_xyz_rpy({1, 2, 3}, {0.3, 0.2, -0.5});
  const Box moved = box.transformed(T);
  const auto a = box.corners(), b = moved.corners();
  for (int i = 0; i < 8; ++i) EXPECT_LT((T * a[i] - b[i]).norm(), 1e-12);
  SplitMix64 rng(5);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d p(rng.uniform01() - 0.5, rng.uniform01() - 0.5, rng.uniform01());
    EXPECT_EQ(box.contains(p), moved.contains((T * p).eval()));
  }
}

TEST(Box, ValidityRejectsBadSizesAndPoses) {
  EXPECT_TRUE(rotated_box().is_valid());
  Box box = rotated_box();
  box.size.x() = 0.0;
  EXPECT_FALSE(box.is_valid());
  box = rotated_box();
  box.size.y() = std::nan("");
  EXPECT_FALSE(box.is_valid());
  box = rotated_box();
  box.pose.linear() *= 2.0;  // not a rotation
  EXPECT_FALSE(box.is_valid());
}

// Membership by an independent construction: a point is inside when its projection on each edge
// direction, measured from corner 0, lies within the edge's length.
bool brute_force_inside(const Box& box, const Eigen::Vector3d& p) {
  const auto c = box.corners();
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Vector3d edge = c[1 << axis] - c[0];
    const double t = (p - c[0]).dot(edge) / edge.squaredNorm();
    if (t < 0.0 || t > 1.0) return false;
  }
  return true;
}

TEST(Crop, OrientedBoxEqualsBruteForceMembership) {
  PointCloud cloud = test::random_cloud(20000, 11);
  cloud.points[7] = Eigen::Vector3f::Constant(std::nanf(""));  // never kept
  const Box box = rotated_box();
  const Indices kept = indices_in_box(cloud, box);
  Indices expected;
  for (Index i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d p = cloud.points[i].cast<double>();
    if (is_finite(cloud.points[i]) && brute_force_inside(box, p)) expected.push_back(i);
  }
  ASSERT_GT(expected.size(), 100u);  // the test means something only if the box holds points
  EXPECT_EQ(kept, expected);
  EXPECT_EQ(crop(cloud, box).size(), expected.size());
}

TEST(Crop, RejectsAnInvalidBox) { EXPECT_THROW(crop(test::random_cloud(10, 1), Box()), Error); }

}  // namespace
}  // namespace lmk
