// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// DistanceField: the unsigned distance to the nearest point of a point set, in a sparse OpenVDB
// grid that covers only a narrow band around the points.
//
// Two grids share one topology: the distance at each voxel centre (a FloatGrid, sampled
// trilinearly), and the index of the point nearest to that centre (an Int32Grid, a closest-point
// transform). Beyond the band the distance is the band value and there is no closest point.
//
// Lifetime: a field is an immutable value; copies share the grids. Thread safety: build a Sampler
// per thread (it caches tree nodes and is not thread-safe itself); any number of samplers may read
// one field concurrently. A sampler keeps the grids alive, so it may outlive its field.

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "lmk/geometry/stop_check.h"

namespace lmk {

struct DistanceFieldSettings {
  double voxel_size = 0.005;  ///< voxel side, m
  double band = 0.02;         ///< distances are exact up to this; beyond, the band value, m
};

class DistanceField {
 public:
  /// An empty field: every distance is the band value.
  DistanceField();
  /// The field of `points` (non-finite points are skipped). Parallel over slabs of points, with
  /// the result independent of the thread count. Throws lmk::Error for a non-positive voxel or a
  /// band smaller than one voxel.
  /// `stop` is called between pieces of the work (geometry/stop_check.h).
  DistanceField(const std::vector<Eigen::Vector3f>& points, const DistanceFieldSettings& settings,
                const StopCheck& stop = {});

  double voxel_size() const;
  double band() const;
  /// Voxels within the band.
  std::size_t active_voxels() const;
  bool empty() const;
  /// The points the field was built from (its closest-point indices refer to them).
  const std::vector<Eigen::Vector3f>& points() const;

  class Sampler {
   public:
    explicit Sampler(const DistanceField& field);
    ~Sampler();
    Sampler(Sampler&&) noexcept;
    /// Trilinear interpolation of the voxel-centre distances; the band value beyond the band.
    float distance(const Eigen::Vector3f& p) const;
    /// The same, with the gradient of the interpolant (zero where the band value is returned).
    float distance(const Eigen::Vector3f& p, Eigen::Vector3f* gradient) const;
    /// Index of the point nearest to the centre of the voxel holding `p`, or -1 beyond the band.
    int closest(const Eigen::Vector3f& p) const;
    /// closest() of each point, into `indices` (resized): one call for a point set, so that the
    /// lookups' memory reads overlap instead of waiting for each other.
    void closest(const std::vector<Eigen::Vector3f>& points, std::vector<int>& indices) const;

   private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
  };
  Sampler sampler() const { return Sampler(*this); }

  struct Grids;  ///< the OpenVDB grids, for storage (occupancy/internal/grids.h)
  const Grids& grids() const;
  /// Reassembles a field from stored grids and the points they index; see internal/grids.h.
  static DistanceField from_grids(std::vector<Eigen::Vector3f> points, Grids grids);

 private:
  std::shared_ptr<const Grids> grids_;
};

}  // namespace lmk
