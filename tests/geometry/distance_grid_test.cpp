// SPDX-License-Identifier: BSD-3-Clause
// The distance grid (distance_grid.h): exact distances between voxel centres, against a brute
// force over random occupied voxels, and what it says outside its box or with nothing occupied.

#include "lmk/geometry/distance_grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "lmk/geometry/error.h"
#include "lmk/geometry/random.h"

namespace lmk {
namespace {

TEST(DistanceGrid, EqualsTheBruteForceDistanceBetweenVoxelCentres) {
  DistanceGrid grid({0, 0, 0}, {0.3, 0.2, 0.25}, 0.01);
  SplitMix64 rng(7);
  std::vector<Eigen::Vector3d> occupied;
  for (int i = 0; i < 25; ++i) {
    const Eigen::Vector3d p(0.3 * rng.uniform01(), 0.2 * rng.uniform01(), 0.25 * rng.uniform01());
    grid.occupy(p);
    occupied.push_back(((p / 0.01).array().floor() + 0.5).matrix() * 0.01);  // its voxel's centre
  }
  grid.compute();
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector3d q(0.3 * rng.uniform01(), 0.2 * rng.uniform01(), 0.25 * rng.uniform01());
    const Eigen::Vector3d centre = ((q / 0.01).array().floor() + 0.5).matrix() * 0.01;
    double nearest = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& o : occupied) nearest = std::min(nearest, (o - centre).norm());
    EXPECT_NEAR(grid.distance(q), nearest, 1e-5);
    // And within the error bound of the distance from the query point itself.
    double exact = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& o : occupied) exact = std::min(exact, (o - q).norm());
    EXPECT_LE(std::abs(grid.distance(q) - exact), grid.error_bound());
  }
}

TEST(DistanceGrid, OutsideItsBoxAndWithNothingOccupied) {
  DistanceGrid grid({0, 0, 0}, {0.1, 0.1, 0.1}, 0.01);
  grid.compute();
  EXPECT_TRUE(std::isinf(grid.distance({0.05, 0.05, 0.05})));  // nothing anywhere
  DistanceGrid one({0, 0, 0}, {0.1, 0.1, 0.1}, 0.01);
  one.occupy({0.055, 0.055, 0.055});
  one.compute();
  EXPECT_NEAR(one.distance({0.055, 0.055, 0.055}), 0.0, 1e-9);
  // Outside, a lower bound: the distance to the box.
  EXPECT_NEAR(one.distance({0.3, 0.05, 0.05}), 0.2, 1e-9);
  EXPECT_THROW(DistanceGrid({0, 0, 0}, {1, 1, 1}, 0.0), Error);
  EXPECT_THROW(DistanceGrid({0, 0, 0}, {1, 1, 1}, 0.001, 1000), Error);  // too many voxels
}

}  // namespace
}  // namespace lmk
