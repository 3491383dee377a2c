// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Voxels regrouped by tiles of 4 x 4 x 4 for lookups of their neighbours (internal/: shared within
// lmk, not installed).
//
// A VoxelTable hashes every voxel to its own slot: the neighbours of one voxel lie anywhere in its
// megabyte of keys, and the normals' eight lookups per voxel each missed the cache (60% of their
// time went to the probe and the record it found). Here a small table finds the tile, a 64-bit
// mask says which of its voxels exist, and the voxels of a tile sit side by side in tile order: a
// block's neighbours are a few neighbouring records, and the table of tiles stays in cache.

#include <cstdint>
#include <vector>

#include "lmk/geometry/internal/voxel_key.h"
#include "lmk/geometry/internal/voxel_table.h"

namespace lmk::detail {

class VoxelTiles {
 public:
  static constexpr std::uint32_t kAbsent = VoxelTable::kAbsent;

  /// Voxels 0 .. count-1, each at coord_of(v), distinct: their places in tile order.
  template <class CoordOf>
  VoxelTiles(std::size_t count, CoordOf coord_of) : table_(count / 8 + 16) {
    std::vector<std::uint32_t> tile_of(count);
    std::uint64_t last_key = kNoVoxel;  // voxels in order of first appearance: often the same tile
    std::uint32_t last_tile = 0;
    for (std::size_t v = 0; v < count; ++v) {
      const VoxelCoord c = coord_of(v);
      const std::uint64_t key = tile_key(c);
      if (key != last_key) last_tile = table_.insert(key), last_key = key;
      tile_of[v] = last_tile;
      if (tile_of[v] == tiles_.size()) tiles_.emplace_back();
      tiles_[tile_of[v]].mask |= bit_of(c);
    }
    std::uint32_t first = 0;
    for (Tile& t : tiles_) {
      t.first = first;
      first += static_cast<std::uint32_t>(__builtin_popcountll(t.mask));
    }
    order_.resize(count);
    for (std::size_t v = 0; v < count; ++v) {
      order_[place(tiles_[tile_of[v]], bit_of(coord_of(v)))] = static_cast<std::uint32_t>(v);
    }
  }

  /// The voxel at each place in tile order: records copied in this order are what find() indexes.
  const std::vector<std::uint32_t>& order() const { return order_; }

  /// The last tile a run of lookups found: neighbouring voxels mostly share one.
  struct Hint {
    std::uint64_t key = kNoVoxel;
    std::uint32_t tile = kAbsent;
  };

  /// The place in tile order of the voxel at `c`, or kAbsent.
  std::uint32_t find(const VoxelCoord& c) const {
    Hint hint;
    return find(c, hint);
  }
  /// The same, the tile looked up only when `hint` holds another.
  std::uint32_t find(const VoxelCoord& c, Hint& hint) const {
    const std::uint64_t key = tile_key(c);
    if (key != hint.key) hint.key = key, hint.tile = table_.find(key);
    if (hint.tile == kAbsent) return kAbsent;
    const std::uint64_t bit = bit_of(c);
    return (tiles_[hint.tile].mask & bit) != 0 ? place(tiles_[hint.tile], bit) : kAbsent;
  }

 private:
  struct Tile {
    std::uint64_t mask = 0;   ///< bit (x % 4) * 16 + (y % 4) * 4 + z % 4 set for each voxel held
    std::uint32_t first = 0;  ///< the place of its first voxel
  };

  // Arithmetic shifts and masks: floor division and its remainder for negative coordinates too.
  static std::uint64_t tile_key(const VoxelCoord& c) {
    return pack_voxel({c[0] >> 2, c[1] >> 2, c[2] >> 2});
  }
  static std::uint64_t bit_of(const VoxelCoord& c) {
    return std::uint64_t{1} << (((c[0] & 3) << 4) | ((c[1] & 3) << 2) | (c[2] & 3));
  }
  // The voxels of a tile keep the order of their bits.
  static std::uint32_t place(const Tile& t, std::uint64_t bit) {
    return t.first + static_cast<std::uint32_t>(__builtin_popcountll(t.mask & (bit - 1)));
  }

  VoxelTable table_;
  std::vector<Tile> tiles_;
  std::vector<std::uint32_t> order_;
};

}  // namespace lmk::detail
