// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A dense grid of the distance from each voxel centre to the nearest occupied voxel, over a box
// (issue #60): the exact Euclidean distance transform of the voxels (Felzenszwalb and
// Huttenlocher's lower envelope of parabolas, one axis after another). A lookup costs one memory
// read, so a motion's thousands of spheres are tested against the scene at once, and only those
// the grid cannot clear are measured exactly.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace lmk {

class DistanceGrid {
 public:
  /// A grid over the axis-aligned `min`-`max` (world frame) of cubic voxels of side `voxel`, with
  /// nothing occupied. Throws lmk::Error for a non-positive voxel, an empty box, or more than
  /// `max_voxels` voxels.
  DistanceGrid(const Eigen::Vector3d& min, const Eigen::Vector3d& max, double voxel,
               std::size_t max_voxels = 64u << 20);

  /// Marks the voxel holding `p` occupied (a point outside the grid is ignored).
  void occupy(const Eigen::Vector3d& p);
  /// Marks every voxel whose centre `is_occupied` says so.
  template <class Predicate>
  void occupy_where(Predicate is_occupied) {
    for (std::size_t i = 0; i < cells_.size(); ++i)
      if (is_occupied(centre(i))) cells_[i] = 0.0f;
  }
  /// Computes the distances; before it, every lookup is +infinity.
  void compute();

  /// The distance from the centre of the voxel holding `p` to the nearest occupied voxel's centre,
  /// m: within error_bound() of the distance from `p` to the nearest occupied point. Outside the
  /// grid: the distance to the grid's box (nothing beyond it is known to the grid).
  double distance(const Eigen::Vector3d& p) const;
  /// How far distance() may lie from the true distance to the occupied points: a voxel's diagonal.
  double error_bound() const;

  double voxel() const { return voxel_; }
  const Eigen::Vector3i& dims() const { return dims_; }
  Eigen::Vector3d centre(std::size_t index) const;

 private:
  std::size_t index(const Eigen::Vector3i& c) const {
    return (static_cast<std::size_t>(c.z()) * dims_.y() + c.y()) * dims_.x() + c.x();
  }
  Eigen::Vector3d min_;
  double voxel_;
  Eigen::Vector3i dims_;
  std::vector<float> cells_;  // squared distances in voxels until compute(), then metres
  bool computed_ = false;
};

}  // namespace lmk
