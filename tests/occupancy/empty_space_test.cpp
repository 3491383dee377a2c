// SPDX-License-Identifier: BSD-3-Clause
// Free space seen by a sensor in front of a plane: empty in front, unknown behind.

#include "lmk/occupancy/empty_space.h"

#include <gtest/gtest.h>

#include <optional>
#include <set>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/random.h"
#include "lmk/occupancy/occupancy_grid.h"

namespace lmk {
namespace {

// A wall at z = 1 m seen from the origin, sampled every 5 mm over 40 x 40 cm.
std::vector<Eigen::Vector3f> wall() {
  std::vector<Eigen::Vector3f> points;
  for (int i = -40; i <= 40; ++i)
    for (int j = -40; j <= 40; ++j) points.emplace_back(0.005f * i, 0.005f * j, 1.0f);
  return points;
}

TEST(EmptySpace, SpaceInFrontOfAPlaneIsEmptyAndBehindItUnknown) {
  const auto points = wall();
  // A 20 cm box straddling the wall: 10 cm in front of it, 10 cm behind.
  const Box box(pose_from_xyz_rpy({0, 0, 1.0}, {0, 0, 0}), {0.2, 0.2, 0.2});
  const DistanceField surface(points, {0.005, 0.02});
  const EmptySpaceSettings settings{0.005, 0.01};
  const EmptySpaceGrid empty =
      EmptySpaceGrid::observe(points, Eigen::Vector3d::Zero(), box, surface, settings);
  EXPECT_GT(empty.size(), 0u);
  EXPECT_TRUE(empty.is_empty({0.0f, 0.0f, 0.95f}));
  EXPECT_TRUE(empty.is_empty({0.05f, -0.05f, 0.92f}));
  EXPECT_FALSE(empty.is_empty({0.0f, 0.0f, 1.05f}));   // occluded: unknown
  EXPECT_FALSE(empty.is_empty({0.0f, 0.0f, 0.995f}));  // within the margin of the surface
  EXPECT_FALSE(empty.is_empty({0.0f, 0.0f, 0.8f}));    // outside the box
  for (const auto& c : empty.centres()) {
    EXPECT_LT(c.z(), 1.0f - 0.01f + 0.0026f);  // nothing at or behind the wall
    EXPECT_TRUE(Box(box.pose, box.size.array() + 1e-5).contains(c));  // float rounding
  }
}

TEST(EmptySpace, BadInputIsAnError) {
  const auto points = wall();
  const DistanceField surface(points, {0.005, 0.02});
  const Box box(Eigen::Isometry3d::Identity(), {0.1, 0.1, 0.1});
  EXPECT_THROW(EmptySpaceGrid::observe(points, Eigen::Vector3d::Zero(), box, surface, {0.0, 0.01}),
               Error);
  EXPECT_THROW(
      EmptySpaceGrid::observe(points, Eigen::Vector3d::Constant(NAN), box, surface, {0.005, 0.01}),
      Error);
  EXPECT_THROW(EmptySpaceGrid::observe(points, Eigen::Vector3d::Zero(),
                                       Box(Eigen::Isometry3d::Identity(), {0, 1, 1}), surface,
                                       {0.005, 0.01}),
               Error);
}

TEST(OccupancyGrid, MarksTheVoxelsHoldingPoints) {
  const OccupancyGrid grid({{0.0f, 0.0f, 0.0f}, {0.1f, 0.0f, 0.0f}}, 0.01);
  const auto s = grid.sampler();
  EXPECT_EQ(grid.occupied_voxels(), 2u);
  EXPECT_TRUE(s.occupied({0.004f, 0.0f, 0.0f}));
  EXPECT_FALSE(s.occupied({0.05f, 0.0f, 0.0f}));
  EXPECT_FALSE(s.occupied({NAN, 0.0f, 0.0f}));
}

TEST(OccupancyGrid, OccupiedInABoxAgreesWithTestingEveryVoxel) {
  // A scattered cloud over several leaf nodes, and a tilted box across them: the leaf-by-leaf
  // query must return exactly the occupied voxels whose centre the box contains.
  std::vector<Eigen::Vector3f> points;
  SplitMix64 rng(4);
  for (int k = 0; k < 3000; ++k) {
    points.emplace_back(rng.uniform01() - 0.5, rng.uniform01() - 0.5, rng.uniform01() - 0.5);
  }
  const double voxel = 0.01;
  const OccupancyGrid grid(points, voxel);
  const Box box(pose_from_xyz_rpy({0.05, -0.1, 0.02}, {0.4, -0.3, 1.1}), {0.3, 0.2, 0.25});
  std::set<std::array<int, 3>> expected, got;
  const auto sampler = grid.sampler();
  for (int x = -60; x <= 60; ++x)
    for (int y = -60; y <= 60; ++y)
      for (int z = -60; z <= 60; ++z) {
        const Eigen::Vector3d centre = Eigen::Vector3d(x, y, z) * voxel;
        if (box.contains(centre) && sampler.occupied(centre.cast<float>())) {
          expected.insert({x, y, z});
        }
      }
  for (const Eigen::Vector3f& c : grid.occupied_in(box)) {
    const Eigen::Vector3i v = (c.cast<double>() / voxel).array().round().cast<int>();
    got.insert({v.x(), v.y(), v.z()});
  }
  EXPECT_GT(expected.size(), 20u);
  EXPECT_EQ(got, expected);
  EXPECT_EQ(grid.occupied_in(box).size(), expected.size());  // no voxel twice
}

TEST(EmptySpace, SamplerAgreesWithTheGridAndOutlivesIt) {
  const auto points = wall();
  const Box box(pose_from_xyz_rpy({0, 0, 1.0}, {0, 0, 0}), {0.2, 0.2, 0.2});
  const DistanceField surface(points, {0.005, 0.02});
  std::optional<EmptySpaceGrid::Sampler> sampler;
  {
    const EmptySpaceGrid empty = EmptySpaceGrid::observe(points, Eigen::Vector3d::Zero(), box,
                                                         surface, EmptySpaceSettings{0.005, 0.01});
    sampler.emplace(empty.sampler());
    for (const auto& c : empty.centres()) EXPECT_TRUE(sampler->is_empty(c));
  }
  EXPECT_TRUE(sampler->is_empty({0.0f, 0.0f, 0.95f}));
  EXPECT_FALSE(sampler->is_empty({0.0f, 0.0f, 1.05f}));
  EXPECT_FALSE(sampler->is_empty({NAN, 0.0f, 0.95f}));
}

}  // namespace
}  // namespace lmk
