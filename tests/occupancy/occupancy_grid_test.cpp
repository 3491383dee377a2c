// SPDX-License-Identifier: BSD-3-Clause
// OccupancyGrid: exactly the voxels nearest to the points are occupied, on both sides of the
// origin, across leaf boundaries, and for a point far from the others.

#include "lmk/occupancy/occupancy_grid.h"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <tuple>

namespace lmk {
namespace {

using Voxel = std::tuple<long, long, long>;

// As OpenVDB's cell-centred voxels: the centre nearest, halves rounded up.
Voxel nearest(const Eigen::Vector3f& p, double voxel) {
  const auto r = [&](float v) {
    return static_cast<long>(std::floor(static_cast<double>(v) * (1.0 / voxel) + 0.5));
  };
  return {r(p.x()), r(p.y()), r(p.z())};
}

TEST(OccupancyGrid, TheVoxelsNearestToThePointsAndNoOthers) {
  const double voxel = 0.01;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-0.3f, 0.3f);
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < 3000; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  // Runs of one voxel and of one leaf, as neighbouring pixels give them.
  for (int i = 0; i < 200; ++i) points.push_back(points[i] + Eigen::Vector3f(0.001f, 0, 0));
  points.emplace_back(std::nanf(""), 0.0f, 0.0f);
  points.emplace_back(2.0e6f, -1.5e6f, 3.0f);  // far from the rest: a leaf of its own
  const OccupancyGrid grid(points, voxel);

  std::set<Voxel> expected;
  for (const Eigen::Vector3f& p : points) {
    if (p.allFinite()) expected.insert(nearest(p, voxel));
  }
  EXPECT_EQ(grid.occupied_voxels(), expected.size());
  const OccupancyGrid::Sampler sampler(grid);
  for (const Eigen::Vector3f& p : points) {
    if (!p.allFinite()) continue;
    EXPECT_TRUE(sampler.occupied(p)) << p.transpose();
  }
  // Every voxel centre of the cube: occupied exactly when expected.
  for (long x = -32; x <= 32; ++x)
    for (long y = -32; y <= 32; ++y)
      for (long z = -32; z <= 32; ++z) {
        const Eigen::Vector3f centre = Eigen::Vector3f(x, y, z) * static_cast<float>(voxel);
        EXPECT_EQ(sampler.occupied(centre), expected.count({x, y, z}) == 1)
            << x << " " << y << " " << z;
      }
}

TEST(OccupancyGrid, NoPointNothingOccupied) {
  const OccupancyGrid grid({}, 0.01);
  EXPECT_EQ(grid.occupied_voxels(), 0u);
  EXPECT_FALSE(OccupancyGrid::Sampler(grid).occupied(Eigen::Vector3f::Zero()));
}

}  // namespace
}  // namespace lmk
