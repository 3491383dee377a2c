// SPDX-License-Identifier: BSD-3-Clause
// The leaf table (occupancy/internal/leaf_table.h) against OpenVDB's own lookups: the same leaf for
// every voxel, negative coordinates and voxels beyond the leaves included; no table where a tree
// holds tiles or spans too many leaves. And the field's closest-point lookups, which read through
// it, against the tree read voxel by voxel.

#include "lmk/occupancy/internal/leaf_table.h"

#include <gtest/gtest.h>

#include "lmk/geometry/random.h"
#include "lmk/occupancy/distance_field.h"
#include "lmk/occupancy/internal/grids.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

using Table = detail::LeafTable<openvdb::Int32Tree>;

TEST(LeafTable, FindsTheTreesOwnLeafForEveryVoxelAroundIt) {
  openvdb::Int32Tree tree(-1);
  SplitMix64 rng(4);
  for (int n = 0; n < 60; ++n) {  // leaves scattered on both sides of the origin
    const openvdb::Coord c(static_cast<int>(rng.uniform01() * 200) - 100,
                           static_cast<int>(rng.uniform01() * 200) - 100,
                           static_cast<int>(rng.uniform01() * 60) - 30);
    tree.setValue(c, n);
  }
  const Table table(tree, /*tiles_checked=*/false);
  ASSERT_TRUE(table.usable());
  int with_leaf = 0;
  for (int x = -120; x < 120; x += 3) {
    for (int y = -120; y < 120; y += 3) {
      for (int z = -40; z < 40; ++z) {
        const openvdb::Coord c(x, y, z);
        const auto* expected = tree.probeConstLeaf(c);
        const Table::Entry found = table.find(c);
        ASSERT_EQ(found.leaf, expected) << c;
        if (expected) {
          ASSERT_EQ(found.values[Table::Leaf::coordToOffset(c)], expected->getValue(c)) << c;
        }
        with_leaf += expected != nullptr;
      }
    }
  }
  EXPECT_GT(with_leaf, 1000);
}

TEST(LeafTable, AnEmptyTreeIsBackgroundEverywhere) {
  const openvdb::Int32Tree tree(-1);
  const Table table(tree, false);
  ASSERT_TRUE(table.usable());
  EXPECT_EQ(table.find(openvdb::Coord(0, 0, 0)).leaf, nullptr);
  EXPECT_EQ(table.find(openvdb::Coord(-5, 7, 1000)).values, nullptr);
}

TEST(LeafTable, IsUnusableWhereATreeHoldsATile) {
  openvdb::Int32Tree active(-1);
  active.addTile(1, openvdb::Coord(0, 0, 0), 3, true);
  EXPECT_FALSE(Table(active, false).usable());
  openvdb::Int32Tree other_value(-1);
  other_value.addTile(1, openvdb::Coord(0, 0, 0), 3, false);
  EXPECT_FALSE(Table(other_value, false).usable());
  // An inactive tile of the background reads as the table would answer.
  openvdb::Int32Tree background(-1);
  background.addTile(1, openvdb::Coord(0, 0, 0), -1, false);
  background.setValue(openvdb::Coord(200, 0, 0), 1);
  EXPECT_TRUE(Table(background, false).usable());
}

TEST(LeafTable, IsUnusableWhereTheLeavesSpanTooLargeABox) {
  openvdb::Int32Tree tree(-1);
  tree.setValue(openvdb::Coord(0, 0, 0), 1);
  // 200 leaves apart on each axis: 8 million entries, beyond the table's limit.
  tree.setValue(openvdb::Coord(1600, 1600, 1600), 2);
  EXPECT_FALSE(Table(tree, false).usable());
}

TEST(LeafTable, TheFieldsClosestPointsAreTheTreesValues) {
  const PointCloud cloud = test::random_cloud(500, 21, 0.3f);
  const double voxel = 0.01;
  const DistanceField field(cloud.points, {voxel, 0.04});
  ASSERT_TRUE(field.grids().closest_leaves.usable());
  const auto access = field.grids().closest->getConstAccessor();
  const auto sampler = field.sampler();
  SplitMix64 rng(6);
  std::vector<Eigen::Vector3f> queries;
  for (int n = 0; n < 20000; ++n) {  // within the band, beyond it, and a non-finite one
    queries.push_back(cloud.points[n % cloud.size()] +
                      0.1f * Eigen::Vector3f(rng.uniform01() - 0.5f, rng.uniform01() - 0.5f,
                                             rng.uniform01() - 0.5f));
  }
  queries.push_back(Eigen::Vector3f(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f));
  std::vector<int> batch;
  sampler.closest(queries, batch);
  // The voxel whose centre is nearest, halves rounded up, as the sampler finds it.
  const double inverse = 1.0 / voxel;
  const auto nearest = [&](float v) {
    return static_cast<int>(std::floor(static_cast<double>(v) * inverse + 0.5));
  };
  int beyond = 0;
  for (std::size_t n = 0; n < queries.size(); ++n) {
    const Eigen::Vector3f& q = queries[n];
    const int expected =
        q.allFinite()
            ? access.getValue(openvdb::Coord(nearest(q.x()), nearest(q.y()), nearest(q.z())))
            : -1;
    ASSERT_EQ(sampler.closest(q), expected) << q.transpose();
    ASSERT_EQ(batch[n], expected) << q.transpose();
    beyond += expected < 0;
  }
  EXPECT_GT(beyond, 100);
}

}  // namespace
}  // namespace lmk
