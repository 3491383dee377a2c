// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/detail/relief_seeds.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include "lmk/geometry/detail/voxel_key.h"
#include "lmk/geometry/random.h"

namespace lmk::detail {

Indices points_near_relief(const PointCloud& cloud, double cell, double angle) {
  const double inv_cell = 1.0 / cell;
  struct Cell {
    Eigen::Vector3f normal_sum = Eigen::Vector3f::Zero();
    bool relief = false;
  };
  std::unordered_map<std::uint64_t, Cell> cells;
  std::vector<VoxelCoord> coords(cloud.size());
  std::vector<char> usable(cloud.size(), 0);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!cloud.points[i].allFinite() || !cloud.normals[i].allFinite()) continue;
    usable[i] = 1;
    coords[i] = voxel_coord(cloud.points[i], inv_cell);
    cells[pack_voxel(coords[i])].normal_sum += cloud.normals[i];
  }
  // A cell has relief when one of its normals leaves the cell's mean direction by more than half
  // the angle (two normals on either side are then about `angle` apart).
  const float min_cos = static_cast<float>(std::cos(0.5 * angle));
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!usable[i]) continue;
    Cell& c = cells[pack_voxel(coords[i])];
    if (c.relief) continue;
    const Eigen::Vector3f mean = c.normal_sum.normalized();
    c.relief = !(cloud.normals[i].dot(mean) >= min_cos);
  }
  Indices out;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!usable[i]) continue;
    bool near = false;
    for (int dx = -1; dx <= 1 && !near; ++dx) {
      for (int dy = -1; dy <= 1 && !near; ++dy) {
        for (int dz = -1; dz <= 1 && !near; ++dz) {
          const VoxelCoord n = {coords[i][0] + dx, coords[i][1] + dy, coords[i][2] + dz};
          const auto it = cells.find(pack_voxel(n));
          near = it != cells.end() && it->second.relief;
        }
      }
    }
    if (near) out.push_back(static_cast<Index>(i));
  }
  return out;
}

namespace {

// Which candidate a cell keeps: a 64-bit hash of (seed, index).
std::uint64_t draw(std::uint64_t seed, std::uint64_t index) {
  return splitmix64_mix(seed * 0x9E3779B97F4A7C15ULL + index + 1);
}

}  // namespace

Indices spread_seeds(const PointCloud& cloud, const Indices& candidates, double spacing,
                     std::uint64_t seed) {
  const double inv_cell = 1.0 / spacing;
  struct Choice {
    std::uint64_t draw;
    Index index;
  };
  std::map<std::uint64_t, Choice> cells;  // ordered: the seeds come out in cell order
  for (Index i : candidates) {
    const std::uint64_t key = pack_voxel(voxel_coord(cloud.points[i], inv_cell));
    const Choice c{draw(seed, i), i};
    const auto [it, inserted] = cells.emplace(key, c);
    if (!inserted &&
        (c.draw < it->second.draw || (c.draw == it->second.draw && c.index < it->second.index))) {
      it->second = c;
    }
  }
  Indices out;
  out.reserve(cells.size());
  for (const auto& [key, choice] : cells) out.push_back(choice.index);
  return out;
}

}  // namespace lmk::detail
