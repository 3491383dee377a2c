// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Voxel coordinates packed into one 64-bit key, shared by the voxel filters and the
// grids above them (internal/: shared within lmk, not installed).

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>

#include "lmk/geometry/error.h"

namespace lmk::detail {

// 21 bits per axis, offset to be non-negative, so that sorting packed keys sorts voxels
// lexicographically by (x, y, z). Keys stay below 2^63: kNoVoxel never collides with one.
constexpr int kVoxelKeyBits = 21;
constexpr std::int64_t kVoxelKeyOffset = std::int64_t{1} << (kVoxelKeyBits - 1);
constexpr std::uint64_t kNoVoxel = ~std::uint64_t{0};

using VoxelCoord = std::array<std::int64_t, 3>;

/// The voxel holding `p` for voxels of side 1 / inv_leaf anchored at the origin. Throws lmk::Error
/// when a coordinate does not fit the key.
inline VoxelCoord voxel_coord(const Eigen::Vector3f& p, double inv_leaf) {
  VoxelCoord c;
  for (int a = 0; a < 3; ++a) {
    const double v = static_cast<double>(p[a]) * inv_leaf;
    // The key's range tested on v itself (floor(v) < -offset exactly when v < -offset, the bound
    // being an integer), so that the cast below only sees values it can hold.
    if (!(v >= static_cast<double>(-kVoxelKeyOffset) && v < static_cast<double>(kVoxelKeyOffset))) {
      throw Error(
          "voxel filter: the cloud spans more than 2^21 voxels along an axis; use a larger leaf "
          "size or crop the cloud");
    }
    // floor(v), inline: std::floor is a libm call on the baseline x86-64 instruction set, and the
    // voxel filters take three per raw point.
    const auto truncated = static_cast<std::int64_t>(v);
    c[a] = truncated - (v < static_cast<double>(truncated) ? 1 : 0);
  }
  return c;
}

inline std::uint64_t pack_voxel(const VoxelCoord& c) {
  std::uint64_t key = 0;
  for (int a = 0; a < 3; ++a) {
    key = (key << kVoxelKeyBits) | static_cast<std::uint64_t>(c[a] + kVoxelKeyOffset);
  }
  return key;
}

}  // namespace lmk::detail
