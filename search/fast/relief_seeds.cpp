// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/fast/relief_seeds.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "lmk/geometry/internal/voxel_key.h"
#include "lmk/geometry/internal/voxel_table.h"
#include "lmk/geometry/principal_axes.h"
#include "lmk/geometry/random.h"

namespace lmk::detail {

namespace {

// Which candidate a cell keeps: a 64-bit hash of (seed, index).
std::uint64_t draw(std::uint64_t seed, std::uint64_t index) {
  return splitmix64_mix(seed * 0x9E3779B97F4A7C15ULL + index + 1);
}

// A cell's points as moments about the cell's corner (PrincipalAxes' convention, well
// conditioned), for the normal test and for their spread off the best plane.
struct ReliefCell {
  VoxelCoord coord;
  Eigen::Vector3f normal_sum = Eigen::Vector3f::Zero();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  double count = 0.0;
  bool spread_normals = false;
  bool relief = false;
};

Eigen::Vector3d corner_of(const VoxelCoord& c, double cell) {
  return Eigen::Vector3d(c[0], c[1], c[2]) * cell;
}

// Whether the cell's points stand off their best plane by more than the sensor's noise at their
// depth explains: the smallest principal variance against one measurement's variance. Too few
// points to fit a plane: the normals decide.
bool beyond_noise(const ReliefCell& c, const ReliefTest& test,
                  const Eigen::Isometry3d& T_sensor_cloud) {
  if (c.count < 4.0) return true;
  const PrincipalAxes pca = principal_axes_from_moments(c.count, c.sum, c.outer);
  const double depth = (T_sensor_cloud * (corner_of(c.coord, test.cell) + pca.mean)).z();
  const double sigma = test.noise.measurement_sigma(std::max(depth, 0.0));
  return pca.spread[0] / c.count > sigma * sigma;
}

}  // namespace

Indices points_near_relief(const PointCloud& cloud, const ReliefTest& test) {
  const double inv_cell = 1.0 / test.cell;
  VoxelTable table(cloud.size() / 64);  // cell key -> index in `cells`
  std::vector<ReliefCell> cells;
  std::vector<std::uint32_t> cell_of(cloud.size(), VoxelTable::kAbsent);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!cloud.points[i].allFinite() || !cloud.normals[i].allFinite()) continue;
    const VoxelCoord coord = voxel_coord(cloud.points[i], inv_cell);
    const std::uint32_t id = table.insert(pack_voxel(coord));
    if (id == cells.size()) cells.push_back({coord});
    ReliefCell& c = cells[id];
    const Eigen::Vector3d p = cloud.points[i].cast<double>() - corner_of(coord, test.cell);
    c.normal_sum += cloud.normals[i];
    c.sum += p;
    c.outer += p * p.transpose();
    c.count += 1.0;
    cell_of[i] = id;
  }
  // The normal test: one of the cell's normals leaves their mean direction by more than half the
  // angle (two normals on either side are then about `angle` apart).
  for (ReliefCell& c : cells) c.normal_sum.normalize();
  const float min_cos = static_cast<float>(std::cos(0.5 * test.angle));
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (cell_of[i] == VoxelTable::kAbsent) continue;
    ReliefCell& c = cells[cell_of[i]];
    if (!c.spread_normals) c.spread_normals = !(cloud.normals[i].dot(c.normal_sum) >= min_cos);
  }
  const std::optional<Eigen::Isometry3d> T_sensor_cloud =
      test.T_cloud_sensor ? std::optional<Eigen::Isometry3d>(test.T_cloud_sensor->inverse())
                          : std::nullopt;
  for (ReliefCell& c : cells) {
    c.relief = c.spread_normals && (!T_sensor_cloud || beyond_noise(c, test, *T_sensor_cloud));
  }
  // A cell is near relief when it or one of its 26 neighbours is relief.
  std::vector<char> near(cells.size(), 0);
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const VoxelCoord& c = cells[k].coord;
    for (int dx = -1; dx <= 1 && !near[k]; ++dx) {
      for (int dy = -1; dy <= 1 && !near[k]; ++dy) {
        for (int dz = -1; dz <= 1 && !near[k]; ++dz) {
          const std::uint32_t id = table.find(pack_voxel({c[0] + dx, c[1] + dy, c[2] + dz}));
          near[k] = id != VoxelTable::kAbsent && cells[id].relief;
        }
      }
    }
  }
  Indices out;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (cell_of[i] != VoxelTable::kAbsent && near[cell_of[i]]) out.push_back(static_cast<Index>(i));
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
