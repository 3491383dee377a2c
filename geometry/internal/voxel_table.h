// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A hash table from packed voxel keys to dense ids, in order of first insertion, for the
// voxel filters and the grids above them (internal/: shared within lmk, not installed).
//
// Open addressing with linear probing: the voxel filters insert one key per raw point (300 000 for
// a Kinect frame), and std::unordered_map's node allocation cost several times more than the rest
// of the filter.

#include <cstdint>
#include <vector>

#include "lmk/geometry/internal/voxel_key.h"

namespace lmk::detail {

class VoxelTable {
 public:
  static constexpr std::uint32_t kAbsent = ~std::uint32_t{0};

  explicit VoxelTable(std::size_t expected_voxels) {
    std::size_t capacity = 1024;
    while (capacity < 2 * expected_voxels) capacity *= 2;
    keys_.assign(capacity, kNoVoxel);
    ids_.assign(capacity, kAbsent);
    shift_ = shift_for(capacity);
  }

  /// The id of `key`, inserting it with the next id when new.
  std::uint32_t insert(std::uint64_t key) {
    std::size_t slot = find_slot(key);
    if (keys_[slot] == key) return ids_[slot];
    if (2 * (size_ + 1) > keys_.size()) {
      grow();
      slot = find_slot(key);
    }
    keys_[slot] = key;
    ids_[slot] = static_cast<std::uint32_t>(size_);
    return static_cast<std::uint32_t>(size_++);
  }

  /// The id of `key`, or kAbsent.
  std::uint32_t find(std::uint64_t key) const {
    const std::size_t slot = find_slot(key);
    return keys_[slot] == key ? ids_[slot] : kAbsent;
  }

  std::size_t size() const { return size_; }

 private:
  // The slot holding `key`, or the empty slot where it would go. The table is never more than
  // half full, so the probe ends.
  //
  // Neighbours hash near each other: a voxel's cell of 4 x 4 x 4 voxels picks a run of 64 slots,
  // and its place in the cell the slot within the run. The normals look up each voxel's block of
  // neighbours, and the filters a frame's points in scan order; scattered over the table, each
  // lookup missed the cache (the scene index, one thread: 3-4% faster this way). The run is chosen
  // by Fibonacci hashing: the top bits of cell x 2^64/phi, which depend on every bit of the cell.
  // (Middle bits depend on the key's low bits only, which leave out the x coordinate of a packed
  // voxel: all voxels of a row along x shared one slot, and the probes ran long.)
  std::size_t find_slot(std::uint64_t key) const {
    const std::size_t mask = keys_.size() - 1;
    constexpr std::uint64_t kLow = 3;  // two bits of each coordinate: the place in the cell
    constexpr std::uint64_t kCell =
        ~((kLow << (2 * kVoxelKeyBits)) | (kLow << kVoxelKeyBits) | kLow);
    const std::uint64_t within = (key & kLow) | ((key >> kVoxelKeyBits) & kLow) << 2 |
                                 ((key >> (2 * kVoxelKeyBits)) & kLow) << 4;
    std::size_t slot = static_cast<std::size_t>(
        (((key & kCell) * 0x9E3779B97F4A7C15ull) >> (shift_ + kCellSlotsLog2)) << kCellSlotsLog2 |
        within);
    while (keys_[slot] != key && keys_[slot] != kNoVoxel) slot = (slot + 1) & mask;
    return slot;
  }

  static constexpr int kCellSlotsLog2 = 6;  // 64 slots a cell: 4 x 4 x 4 voxels

  // 64 - log2(capacity): the shift that leaves a slot index.
  static int shift_for(std::size_t capacity) {
    int bits = 0;
    while ((std::size_t{1} << bits) < capacity) ++bits;
    return 64 - bits;
  }

  void grow() {
    std::vector<std::uint64_t> keys(2 * keys_.size(), kNoVoxel);
    std::vector<std::uint32_t> ids(2 * ids_.size(), kAbsent);
    keys.swap(keys_);
    ids.swap(ids_);
    shift_ = shift_for(keys_.size());
    for (std::size_t k = 0; k < keys.size(); ++k) {
      if (keys[k] == kNoVoxel) continue;
      const std::size_t slot = find_slot(keys[k]);
      keys_[slot] = keys[k];
      ids_[slot] = ids[k];
    }
  }

  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> ids_;
  std::size_t size_ = 0;
  int shift_ = 64;
};

}  // namespace lmk::detail
