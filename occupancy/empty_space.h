// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// EmptySpaceGrid: the voxels of a landmark's box that the sensor observed to be free at capture.
//
// This is the paper's empty-space constraint made explicit. A voxel is observed free when a sensor
// ray crossed it before hitting a surface. Voxels behind a surface were occluded: they are
// *unknown*, not empty, and are not stored, so a search never penalises a scene point there.
// Voxels within a margin of the landmark's own points are left out too: depth noise scatters the
// surface over a few millimetres, and that must not count as intrusion. So are voxels next to
// unobserved ones, where a surface the sensor never returned may stand.

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/occupancy/distance_field.h"

namespace lmk {

struct EmptySpaceSettings {
  double voxel_size = 0.005;     ///< voxel side, m
  double surface_margin = 0.01;  ///< free space stops this far before each ray's end point, m
  /// Free space stops this far from every voxel of the box that no ray crossed, m: a surface the
  /// sensor never returned may lie there. One voxel catches a face's points wherever noise puts
  /// them; the full surface margin cost more empty space than it bought (docs/evaluation.md).
  double unobserved_margin = 0.005;
};

/// The rays of one view: from the sensor's origin to each of `ends` (non-finite ends are skipped),
/// all in one frame.
struct RayBundle {
  const std::vector<Eigen::Vector3f>* ends = nullptr;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
};

class EmptySpaceGrid {
 public:
  EmptySpaceGrid();  ///< nothing observed: no voxel is empty

  /// Casts a ray from `sensor_origin` to every point of `scene_points` (the whole capture scene, in
  /// the capture frame: rays that pass through the box and end behind it count) and keeps the
  /// voxels inside `box` that a ray crossed up to `surface_margin` before its end point, that lie
  /// at least `surface_margin` from every point of `surface`, and at least `unobserved_margin`
  /// from every voxel inside `box` that no ray crossed. Throws lmk::Error for a non-positive
  /// voxel, a negative margin or an invalid box.
  static EmptySpaceGrid observe(const std::vector<Eigen::Vector3f>& scene_points,
                                const Eigen::Vector3d& sensor_origin, const Box& box,
                                const DistanceField& surface, const EmptySpaceSettings& settings);

  /// observe() over several views of one landmark (issue #35): a voxel is crossed when a ray of
  /// any view crossed it, so the free space is the union of what each view saw free, and
  /// unobserved when no view's ray crossed it. A voxel one view saw free and another saw a surface
  /// in is not free: `surface` holds every view's points, and free space keeps `surface_margin`
  /// from all of them. One bundle gives observe()'s grid exactly.
  static EmptySpaceGrid observe_views(const std::vector<RayBundle>& views, const Box& box,
                                      const DistanceField& surface,
                                      const EmptySpaceSettings& settings);

  double voxel_size() const;
  std::size_t size() const;  ///< number of empty voxels
  /// The empty voxels' centres, in a deterministic order (by voxel coordinate).
  const std::vector<Eigen::Vector3f>& centres() const;
  /// Whether `p` lies in an empty voxel. Not for hot loops: use a Sampler.
  bool is_empty(const Eigen::Vector3f& p) const;

  /// Cached lookups for one thread (as DistanceField::Sampler); keeps the grid alive.
  class Sampler {
   public:
    explicit Sampler(const EmptySpaceGrid& grid);
    ~Sampler();
    Sampler(Sampler&&) noexcept;
    bool is_empty(const Eigen::Vector3f& p) const;

   private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
  };
  Sampler sampler() const { return Sampler(*this); }

  /// The empty voxels' integer coordinates (a voxel's centre is its coordinate times
  /// voxel_size()), in ascending (x, y, z) order: what a landmark file stores.
  std::vector<Eigen::Vector3i> voxels() const;
  /// The grid of exactly these voxels, of side `voxel_size`. Throws lmk::Error for a voxel side
  /// that is not positive and finite.
  static EmptySpaceGrid from_voxels(double voxel_size, const std::vector<Eigen::Vector3i>& voxels);

  struct Grid;  ///< the OpenVDB grid (occupancy/internal/grids.h)
  const Grid& grid() const;
  static EmptySpaceGrid from_grid(Grid grid);

 private:
  std::shared_ptr<const Grid> grid_;
};

}  // namespace lmk
