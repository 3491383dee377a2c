// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// OccupancyGrid: which voxels of a scene hold at least one point. A landmark's empty voxels, moved
// into a scene, must land on unoccupied voxels; this grid answers that in O(1) per voxel.
//
// Thread safety: as DistanceField, build a Sampler per thread.

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/geometry/stop_check.h"

namespace lmk {

class OccupancyGrid {
 public:
  OccupancyGrid();  ///< nothing occupied
  /// The voxels (side `voxel_size`, m) holding a finite point of `points`. Throws lmk::Error for a
  /// non-positive voxel. `stop` is called between pieces of the work (geometry/stop_check.h).
  OccupancyGrid(const std::vector<Eigen::Vector3f>& points, double voxel_size,
                const StopCheck& stop = {});

  double voxel_size() const;
  std::size_t occupied_voxels() const;
  /// The centres of the occupied voxels whose centre lies inside `box`, in a deterministic order.
  /// Visits only the grid's leaf nodes that the box's bounding box meets: far cheaper than probing
  /// every voxel of a mostly empty box.
  std::vector<Eigen::Vector3f> occupied_in(const Box& box) const;

  class Sampler {
   public:
    explicit Sampler(const OccupancyGrid& grid);
    ~Sampler();
    Sampler(Sampler&&) noexcept;
    bool occupied(const Eigen::Vector3f& p) const;

   private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
  };
  Sampler sampler() const { return Sampler(*this); }

 private:
  struct Grid;
  std::shared_ptr<const Grid> grid_;
};

}  // namespace lmk
