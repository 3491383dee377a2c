// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/detail/relief_seeds.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>

#include "lmk/geometry/detail/voxel_key.h"
#include "lmk/geometry/random.h"

namespace lmk::detail {

namespace {

// Which candidate a cell keeps: a 64-bit hash of (seed, index).
std::uint64_t draw(std::uint64_t seed, std::uint64_t index) {
  return splitmix64_mix(seed * 0x9E3779B97F4A7C15ULL + index + 1);
}

// A cell's points as moments, for the normal test and for their spread off the best plane.
struct ReliefCell {
  VoxelCoord coord;
  Eigen::Vector3f normal_sum = Eigen::Vector3f::Zero();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  std::size_t count = 0;
  bool spread_normals = false;
  bool relief = false;
};

// Whether the cell's points stand off their best plane by more than the sensor's noise at their
// depth explains: the smallest principal variance against one measurement's variance. Too few
// points to fit a plane: the normals decide.
bool beyond_noise(const ReliefCell& c, const ReliefTest& test) {
  if (!test.T_cloud_sensor || c.count < 4) return true;
  const double n = static_cast<double>(c.count);
  const Eigen::Vector3d mean = c.sum / n;
  const Eigen::Matrix3d covariance = c.outer / n - mean * mean.transpose();
  const double off_plane =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance, Eigen::EigenvaluesOnly)
          .eigenvalues()[0];
  const double depth = (test.T_cloud_sensor->inverse() * mean).z();
  const double sigma = test.noise.measurement_sigma(std::max(depth, 0.0));
  return off_plane > sigma * sigma;
}

}  // namespace

Indices points_near_relief(const PointCloud& cloud, const ReliefTest& test) {
  const double inv_cell = 1.0 / test.cell;
  std::unordered_map<std::uint64_t, std::uint32_t> lookup;  // cell key -> index in `cells`
  std::vector<ReliefCell> cells;
  std::vector<std::uint32_t> cell_of(cloud.size(), std::numeric_limits<std::uint32_t>::max());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!cloud.points[i].allFinite() || !cloud.normals[i].allFinite()) continue;
    const VoxelCoord coord = voxel_coord(cloud.points[i], inv_cell);
    const auto [it, inserted] =
        lookup.emplace(pack_voxel(coord), static_cast<std::uint32_t>(cells.size()));
    if (inserted) cells.push_back({coord});
    ReliefCell& c = cells[it->second];
    const Eigen::Vector3d p = cloud.points[i].cast<double>();
    c.normal_sum += cloud.normals[i];
    c.sum += p;
    c.outer += p * p.transpose();
    ++c.count;
    cell_of[i] = it->second;
  }
  // The normal test: one of the cell's normals leaves their mean direction by more than half the
  // angle (two normals on either side are then about `angle` apart).
  const float min_cos = static_cast<float>(std::cos(0.5 * test.angle));
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (cell_of[i] == std::numeric_limits<std::uint32_t>::max()) continue;
    ReliefCell& c = cells[cell_of[i]];
    if (!c.spread_normals)
      c.spread_normals = !(cloud.normals[i].dot(c.normal_sum.normalized()) >= min_cos);
  }
  for (ReliefCell& c : cells) c.relief = c.spread_normals && beyond_noise(c, test);
  // A cell is near relief when it or one of its 26 neighbours is relief.
  std::vector<char> near(cells.size(), 0);
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const VoxelCoord& c = cells[k].coord;
    for (int dx = -1; dx <= 1 && !near[k]; ++dx) {
      for (int dy = -1; dy <= 1 && !near[k]; ++dy) {
        for (int dz = -1; dz <= 1 && !near[k]; ++dz) {
          const auto it = lookup.find(pack_voxel({c[0] + dx, c[1] + dy, c[2] + dz}));
          near[k] = it != lookup.end() && cells[it->second].relief;
        }
      }
    }
  }
  Indices out;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (cell_of[i] != std::numeric_limits<std::uint32_t>::max() && near[cell_of[i]])
      out.push_back(static_cast<Index>(i));
  }
  return out;
}

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
