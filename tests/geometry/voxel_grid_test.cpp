// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/voxel_grid.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <map>
#include <set>

#include "lmk/geometry/error.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

using Voxel = std::array<long long, 3>;

Voxel voxel_of(const Eigen::Vector3f& p, double leaf) {
  return {static_cast<long long>(std::floor(p.x() / leaf)),
          static_cast<long long>(std::floor(p.y() / leaf)),
          static_cast<long long>(std::floor(p.z() / leaf))};
}

TEST(VoxelDownsample, OnePointPerOccupiedVoxelEachInsideItsVoxel) {
  const double leaf = 0.05;
  PointCloud cloud = test::random_cloud(50000, 21, 0.5f);
  cloud.points[0] = Eigen::Vector3f::Constant(std::nanf(""));
  const PointCloud out = voxel_downsample(cloud, leaf);

  std::set<Voxel> occupied;
  for (const auto& p : cloud.points) {
    if (is_finite(p)) occupied.insert(voxel_of(p, leaf));
  }
  ASSERT_EQ(out.size(), occupied.size());
  std::set<Voxel> seen;
  for (const auto& p : out.points) {
    const Voxel v = voxel_of(p, leaf);
    EXPECT_TRUE(seen.insert(v).second) << "two output points share a voxel";
    EXPECT_TRUE(occupied.count(v)) << "output point outside every occupied voxel";
  }
}

TEST(VoxelDownsample, OutputIsTheCentroidOfEachVoxel) {
  const double leaf = 0.1;
  const PointCloud cloud = test::random_cloud(5000, 4, 0.3f);
  std::map<Voxel, std::pair<Eigen::Vector3d, int>> sums;
  for (const auto& p : cloud.points) {
    auto& [sum, n] = sums[voxel_of(p, leaf)];
    if (n == 0) sum.setZero();
    sum += p.cast<double>();
    ++n;
  }
  const PointCloud out = voxel_downsample(cloud, leaf);
  for (const auto& p : out.points) {
    const auto& [sum, n] = sums.at(voxel_of(p, leaf));
    EXPECT_LT((p.cast<double>() - sum / n).norm(), 1e-6);
  }
}

TEST(VoxelDownsample, SameResultWhateverTheThreadCount) {
  const PointCloud cloud = test::random_cloud(100000, 8, 1.0f);
  PointCloud one, two;
  tbb::task_arena(1).execute([&] { one = voxel_downsample(cloud, 0.02); });
  tbb::task_arena(2).execute([&] { two = voxel_downsample(cloud, 0.02); });
  EXPECT_EQ(one.points, two.points);
}

TEST(VoxelDownsample, AveragesAttributes) {
  PointCloud cloud(std::vector<Eigen::Vector3f>{
      {0.01f, 0.01f, 0.01f}, {0.02f, 0.02f, 0.02f}, {0.03f, 0.01f, 0.01f}, {0.5f, 0.5f, 0.5f}});
  cloud.normals = {{0, 0, 1}, {0, 1, 0}, {0, 0, 1}, {1, 0, 0}};
  cloud.colors = {{10, 20, 30, 255}, {20, 40, 60, 255}, {30, 60, 90, 255}, {1, 2, 3, 255}};
  cloud.labels = {7, 3, 3, 1};
  const PointCloud out = voxel_downsample(cloud, 0.1);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_NEAR(out.normals[0].norm(), 1.0f, 1e-6f);
  EXPECT_GT(out.normals[0].z(), out.normals[0].y());
  EXPECT_EQ(out.colors[0], (Color{20, 40, 60, 255}));
  EXPECT_EQ(out.labels[0], 3);  // the most frequent label
  EXPECT_EQ(out.labels[1], 1);
}

TEST(VoxelDownsample, RejectsABadLeaf) {
  const PointCloud cloud = test::random_cloud(10, 1);
  EXPECT_THROW(voxel_downsample(cloud, 0.0), Error);
  EXPECT_THROW(voxel_downsample(cloud, -1.0), Error);
  EXPECT_THROW(voxel_downsample(cloud, std::nan("")), Error);
  EXPECT_THROW(voxel_downsample(test::random_cloud(10, 1, 1000.0f), 1e-4),
               Error);  // too many voxels
}

}  // namespace
}  // namespace lmk
