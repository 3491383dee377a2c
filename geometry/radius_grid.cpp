// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/radius_grid.h"

#include <cmath>
#include <utility>

#include "lmk/geometry/detail/voxel_buckets.h"
#include "lmk/geometry/error.h"

namespace lmk {

RadiusGrid::RadiusGrid(const PointCloud& cloud, double cell) : inv_cell_(1.0 / cell) {
  if (!(cell > 0.0) || !std::isfinite(cell)) {
    throw Error("radius grid: the cell size must be positive and finite");
  }
  detail::VoxelBuckets buckets = detail::bucket_by_voxel(cloud, inv_cell_);
  begin_ = std::move(buckets.starts);
  indices_ = std::move(buckets.members);
  points_.reserve(indices_.size());
  for (const Index i : indices_) points_.push_back(cloud.points[i]);  // contiguous by cell
  cells_ = std::make_unique<detail::VoxelTable>(std::move(buckets.table));
}

RadiusGrid::~RadiusGrid() = default;
RadiusGrid::RadiusGrid(RadiusGrid&&) noexcept = default;
RadiusGrid& RadiusGrid::operator=(RadiusGrid&&) noexcept = default;

// Calls visit(begin, end) with the slots of every cell that may hold a point strictly closer than
// `radius`. The cells scanned are those between the cells of query -/+ radius on each axis: a point
// within the ball lies between those bounds, and flooring the scaled coordinate is monotonic, so
// its cell is among them.
template <class VisitCell>
void RadiusGrid::for_each_cell_within(const Eigen::Vector3f& query, float radius,
                                      VisitCell&& visit) const {
  if (points_.empty() || !(radius > 0.0f) || !query.allFinite()) return;
  const float r2 = radius * radius;  // as KdTree squares it
  detail::VoxelCoord lo, hi;
  for (int a = 0; a < 3; ++a) {
    lo[a] = static_cast<std::int64_t>(
        std::floor((static_cast<double>(query[a]) - static_cast<double>(radius)) * inv_cell_));
    hi[a] = static_cast<std::int64_t>(
        std::floor((static_cast<double>(query[a]) + static_cast<double>(radius)) * inv_cell_));
  }
  const double cell = 1.0 / inv_cell_;
  const auto gap = [&](int a, std::int64_t c) {  // from the query to cell c along axis a, m
    const double low = static_cast<double>(c) * cell, high = low + cell;
    return query[a] < low ? low - query[a] : (query[a] > high ? query[a] - high : 0.0);
  };
  for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
    const double gx = gap(0, x);
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
      const double gy = gap(1, y);
      for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
        const double gz = gap(2, z);
        // Cells wholly outside the ball (with a margin for rounding) are not looked up.
        if (gx * gx + gy * gy + gz * gz > 1.0001 * static_cast<double>(r2)) continue;
        if (x < -detail::kVoxelKeyOffset || x >= detail::kVoxelKeyOffset ||
            y < -detail::kVoxelKeyOffset || y >= detail::kVoxelKeyOffset ||
            z < -detail::kVoxelKeyOffset || z >= detail::kVoxelKeyOffset) {
          continue;
        }
        const std::uint32_t id = cells_->find(detail::pack_voxel({x, y, z}));
        if (id != detail::VoxelTable::kAbsent) visit(begin_[id], begin_[id + 1]);
      }
    }
  }
}

float RadiusGrid::squared_distance(const Eigen::Vector3f& query, std::size_t slot) const {
  const Eigen::Vector3f& p = points_[slot];
  float d2 = 0.0f;
  for (int a = 0; a < 3; ++a) {
    const float diff = query[a] - p[a];
    d2 += diff * diff;
  }
  return d2;
}

void RadiusGrid::radius_unsorted(const Eigen::Vector3f& query, float radius,
                                 std::vector<Neighbor>& out) const {
  out.clear();
  const float r2 = radius * radius;
  // Every point of a cell is written and only those within the ball advance the end: a boundary
  // cell's points fall on both sides about evenly, and a branch on each mispredicted half of them.
  for_each_cell_within(query, radius, [&](std::size_t begin, std::size_t end) {
    std::size_t kept = out.size();
    out.resize(kept + (end - begin));
    for (std::size_t slot = begin; slot < end; ++slot) {
      const float d2 = squared_distance(query, slot);
      out[kept] = {indices_[slot], d2};
      kept += d2 < r2 ? 1 : 0;
    }
    out.resize(kept);
  });
}

std::optional<Neighbor> RadiusGrid::nearest_within(const Eigen::Vector3f& query,
                                                   float radius) const {
  std::optional<Neighbor> best;
  const float r2 = radius * radius;
  for_each_cell_within(query, radius, [&](std::size_t begin, std::size_t end) {
    for (std::size_t slot = begin; slot < end; ++slot) {
      const float d2 = squared_distance(query, slot);
      if (d2 < r2 && (!best || d2 < best->squared_distance ||
                      (d2 == best->squared_distance && indices_[slot] < best->index))) {
        best = Neighbor{indices_[slot], d2};
      }
    }
  });
  return best;
}

}  // namespace lmk
