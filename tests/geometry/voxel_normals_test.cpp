// SPDX-License-Identifier: BSD-3-Clause
// VoxelMoments: the same centroids as voxel_downsample, and normals of planes and lines from the
// pooled moments.

#include "lmk/geometry/voxel_normals.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>

#include "lmk/geometry/error.h"
#include "lmk/geometry/voxel_grid.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

std::vector<Eigen::Vector3f> sorted(std::vector<Eigen::Vector3f> points) {
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  return points;
}

TEST(VoxelMoments, CentroidsAreThoseOfVoxelDownsample) {
  PointCloud cloud = test::random_cloud(20000, 3, 0.5f);
  cloud.points[7] = Eigen::Vector3f::Constant(std::nanf(""));
  const double leaf = 0.05;
  const VoxelMoments moments(cloud, leaf);
  const std::vector<Eigen::Vector3f> ours = sorted(moments.centroids());
  const std::vector<Eigen::Vector3f> theirs = sorted(voxel_downsample(cloud, leaf).points);
  ASSERT_EQ(moments.size(), theirs.size());
  for (std::size_t i = 0; i < ours.size(); ++i) EXPECT_LT((ours[i] - theirs[i]).norm(), 1e-6);
}

TEST(VoxelMoments, NormalsOfATiltedPlaneFaceTheViewpoint) {
  // A plane through the origin with normal n, sampled every 2 mm, seen from the side n points to.
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  PointCloud cloud;
  for (int i = -100; i <= 100; ++i)
    for (int j = -100; j <= 100; ++j)
      cloud.points.push_back((0.002 * (i * u + j * v)).cast<float>());
  const VoxelMoments moments(cloud, 0.01);
  const std::vector<Eigen::Vector3f> normals = moments.normals(2.0 * n);
  std::size_t defined = 0;
  for (const Eigen::Vector3f& normal : normals) {
    if (!is_finite(normal)) continue;
    ++defined;
    EXPECT_GT(normal.cast<double>().dot(n), 0.999);
  }
  EXPECT_EQ(defined, normals.size());
  // Seen from the other side, every normal turns round.
  for (const Eigen::Vector3f& normal : moments.normals(-2.0 * n)) {
    EXPECT_LT(normal.cast<double>().dot(n), -0.999);
  }
}

TEST(VoxelMoments, UndefinedOnALineAndSameWhateverTheThreadCount) {
  PointCloud line;
  for (int i = 0; i < 500; ++i) line.points.emplace_back(0.001f * i, 0.5f, 0.25f);
  for (const Eigen::Vector3f& normal : VoxelMoments(line, 0.01).normals({0, 0, 1})) {
    EXPECT_FALSE(is_finite(normal));
  }
  const PointCloud cloud = test::random_cloud(20000, 5, 0.3f);
  std::vector<Eigen::Vector3f> serial;
  tbb::task_arena(1).execute([&] { serial = VoxelMoments(cloud, 0.02).normals({0, 0, 2}); });
  const std::vector<Eigen::Vector3f> parallel = VoxelMoments(cloud, 0.02).normals({0, 0, 2});
  ASSERT_EQ(serial.size(), parallel.size());
  for (std::size_t i = 0; i < serial.size(); ++i) {
    EXPECT_TRUE(serial[i] == parallel[i] || (!is_finite(serial[i]) && !is_finite(parallel[i])));
  }
  EXPECT_THROW(VoxelMoments(cloud, 0.0), Error);
}

}  // namespace
}  // namespace lmk
