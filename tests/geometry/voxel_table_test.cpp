// SPDX-License-Identifier: BSD-3-Clause
// The voxel table (geometry/internal/voxel_table.h) with the keys a frame gives it: dense blocks
// of neighbours, axis-aligned planes, negative coordinates, and enough of them to grow the table
// several times. Every key keeps the id of its first insertion, and keys never inserted are absent.

#include "lmk/geometry/internal/voxel_table.h"

#include <gtest/gtest.h>

#include <unordered_map>

namespace lmk::detail {
namespace {

TEST(VoxelTable, NeighbouringKeysKeepTheirFirstIdsThroughGrowth) {
  VoxelTable table(16);  // grows from its smallest size
  std::unordered_map<std::uint64_t, std::uint32_t> ids;
  const auto insert = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    const std::uint64_t key = pack_voxel({x, y, z});
    const std::uint32_t id = table.insert(key);
    const auto [it, fresh] = ids.emplace(key, static_cast<std::uint32_t>(ids.size()));
    ASSERT_EQ(id, it->second) << x << " " << y << " " << z << (fresh ? " (new)" : " (again)");
  };
  for (int x = -20; x < 20; ++x)  // a dense block about the origin: whole cells of neighbours
    for (int y = -20; y < 20; ++y)
      for (int z = -6; z < 6; ++z) insert(x, y, z);
  for (int x = -300; x < 300; ++x)  // planes along each axis, as a table top and walls give
    for (int y = -100; y < 100; y += 3) insert(x, y, 40), insert(40, x, y), insert(y, 40, x);
  for (int x = -20; x < 20; ++x) insert(x, 3, -2);  // keys seen before
  EXPECT_EQ(table.size(), ids.size());
  for (const auto& [key, id] : ids) EXPECT_EQ(table.find(key), id);
  // Neighbours of inserted keys that were never inserted themselves.
  for (int x = -20; x < 20; ++x) {
    EXPECT_EQ(table.find(pack_voxel({x, 0, 7})), VoxelTable::kAbsent);
    EXPECT_EQ(table.find(pack_voxel({x, -5000, 0})), VoxelTable::kAbsent);
  }
}

}  // namespace
}  // namespace lmk::detail
