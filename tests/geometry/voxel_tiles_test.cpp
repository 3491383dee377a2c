// SPDX-License-Identifier: BSD-3-Clause
// VoxelTiles: every voxel found at its place in tile order, every other coordinate absent, across
// tile boundaries on both sides of the origin.

#include "lmk/geometry/internal/voxel_tiles.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>

namespace lmk::detail {
namespace {

TEST(VoxelTiles, FindsEachVoxelAtItsPlaceAndNothingElse) {
  // About half of the voxels of a cube spanning 3 tiles either side of the origin, in random order.
  std::mt19937 rng(11);
  std::vector<VoxelCoord> voxels;
  for (std::int64_t x = -12; x < 12; ++x)
    for (std::int64_t y = -12; y < 12; ++y)
      for (std::int64_t z = -12; z < 12; ++z)
        if (rng() % 2 == 0) voxels.push_back({x, y, z});
  std::shuffle(voxels.begin(), voxels.end(), rng);
  const VoxelTiles tiles(voxels.size(), [&](std::size_t v) { return voxels[v]; });

  const std::vector<std::uint32_t>& order = tiles.order();
  ASSERT_EQ(order.size(), voxels.size());
  EXPECT_EQ(std::set<std::uint32_t>(order.begin(), order.end()).size(), voxels.size())
      << "order() is a permutation";
  std::map<VoxelCoord, std::size_t> index;
  for (std::size_t v = 0; v < voxels.size(); ++v) index[voxels[v]] = v;
  for (std::int64_t x = -14; x < 14; ++x)
    for (std::int64_t y = -14; y < 14; ++y)
      for (std::int64_t z = -14; z < 14; ++z) {
        const VoxelCoord c{x, y, z};
        const std::uint32_t place = tiles.find(c);
        const auto it = index.find(c);
        if (it == index.end()) {
          EXPECT_EQ(place, VoxelTiles::kAbsent) << x << " " << y << " " << z;
        } else {
          ASSERT_NE(place, VoxelTiles::kAbsent) << x << " " << y << " " << z;
          EXPECT_EQ(order[place], it->second) << x << " " << y << " " << z;
        }
      }
}

TEST(VoxelTiles, ATileKeepsItsVoxelsTogether) {
  // Two voxels of one tile and one of another, given interleaved: the tile's two are neighbours in
  // tile order.
  const std::vector<VoxelCoord> voxels = {{0, 0, 0}, {9, 9, 9}, {3, 3, 3}};
  const VoxelTiles tiles(voxels.size(), [&](std::size_t v) { return voxels[v]; });
  const std::uint32_t a = tiles.find(voxels[0]), b = tiles.find(voxels[2]);
  EXPECT_EQ(a > b ? a - b : b - a, 1u);
}

TEST(VoxelTiles, EmptyFindsNothing) {
  const VoxelTiles tiles(0, [](std::size_t) { return VoxelCoord{}; });
  EXPECT_TRUE(tiles.order().empty());
  EXPECT_EQ(tiles.find({0, 0, 0}), VoxelTiles::kAbsent);
}

}  // namespace
}  // namespace lmk::detail
