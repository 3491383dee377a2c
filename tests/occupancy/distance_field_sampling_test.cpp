// SPDX-License-Identifier: BSD-3-Clause
// The field's trilinear sampling against the voxel values read one by one through OpenVDB, where
// a query's cell crosses leaf-node boundaries (its corners then lie in up to eight leaves) and
// where a stored grid holds a tile instead of leaves.

#include <gtest/gtest.h>

#include <cmath>

#include "lmk/geometry/random.h"
#include "lmk/occupancy/distance_field.h"
#include "lmk/occupancy/internal/grids.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

// Trilinear interpolation of the 8 voxel values around q, each read by probeValue; the band where
// none of them is active.
float reference_distance(const openvdb::FloatGrid& grid, double voxel, float band,
                         const Eigen::Vector3f& q) {
  const auto access = grid.getConstAccessor();
  const Eigen::Vector3d x = q.cast<double>() / voxel;
  const Eigen::Vector3d base = x.array().floor();
  const Eigen::Vector3d t = x - base;
  const openvdb::Coord c0(static_cast<int>(base.x()), static_cast<int>(base.y()),
                          static_cast<int>(base.z()));
  double v[2][2][2];
  bool any = false;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k) {
        float value = band;
        any |= access.probeValue(c0.offsetBy(i, j, k), value);
        v[i][j][k] = value;
      }
  if (!any) return band;
  double vy[2];
  for (int i = 0; i < 2; ++i) {
    const double z0 = v[i][0][0] + t.z() * (v[i][0][1] - v[i][0][0]);
    const double z1 = v[i][1][0] + t.z() * (v[i][1][1] - v[i][1][0]);
    vy[i] = z0 + t.y() * (z1 - z0);
  }
  return static_cast<float>(vy[0] + t.x() * (vy[1] - vy[0]));
}

TEST(DistanceFieldSampling, CellsAcrossLeafBoundariesReadEveryCornerFromItsOwnLeaf) {
  const PointCloud cloud = test::random_cloud(300, 5, 0.3f);
  const double voxel = 0.01;
  const DistanceField field(cloud.points, {voxel, 0.04});
  const auto sampler = field.sampler();
  const openvdb::FloatGrid& grid = *field.grids().distance;
  SplitMix64 rng(9);
  int crossing = 0;
  for (int n = 0; n < 20000; ++n) {
    // Points near the points (inside the band), half of them in cells on a leaf's last voxel
    // along some axis, whose corners span two leaves there.
    Eigen::Vector3f q = cloud.points[n % cloud.size()] +
                        0.03f * Eigen::Vector3f(rng.uniform01() - 0.5f, rng.uniform01() - 0.5f,
                                                rng.uniform01() - 0.5f);
    if (n % 2 == 0) {
      const int axis = n / 2 % 3;
      const double cell = std::floor(q[axis] / voxel);
      const double last = 8.0 * std::floor(cell / 8.0) + 7.0;  // the leaf's last voxel
      q[axis] = static_cast<float>((last + rng.uniform01()) * voxel);
      ++crossing;
    }
    EXPECT_NEAR(sampler.distance(q), reference_distance(grid, voxel, 0.04f, q), 1e-6)
        << q.transpose();
  }
  EXPECT_GT(crossing, 5000);
}

TEST(DistanceFieldSampling, AStoredGridsTileIsReadThroughTheAccessor) {
  // A grid with an active tile of value 0.01 over a whole leaf's span and one leaf beside it.
  DistanceField::Grids grids;
  grids.band = 0.05;
  const double voxel = 0.01;
  grids.distance = openvdb::FloatGrid::create(0.05f);
  grids.distance->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
  grids.distance->tree().addTile(1, openvdb::Coord(0, 0, 0), 0.01f, true);
  auto access = grids.distance->getAccessor();
  access.setValueOn(openvdb::Coord(8, 3, 3), 0.03f);  // a leaf at x in [8, 16)
  grids.closest = openvdb::Int32Grid::create(-1);
  const DistanceField field = DistanceField::from_grids({}, std::move(grids));
  const auto sampler = field.sampler();
  const openvdb::FloatGrid& grid = *field.grids().distance;
  // Cells from x = 7 to 8 cross from the tile into the leaf.
  for (double y : {3.2, 3.7}) {
    for (double x : {6.5, 7.25, 7.5, 7.9}) {
      const Eigen::Vector3f q(static_cast<float>(x * voxel), static_cast<float>(y * voxel),
                              static_cast<float>(3.4 * voxel));
      EXPECT_NEAR(sampler.distance(q), reference_distance(grid, voxel, 0.05f, q), 1e-6)
          << q.transpose();
    }
  }
  // Inside the tile, every corner holds 0.01.
  EXPECT_NEAR(sampler.distance(Eigen::Vector3f(0.035f, 0.035f, 0.035f)), 0.01f, 1e-6);
}

}  // namespace
}  // namespace lmk
