// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Iterative closest point: the rigid motion that best aligns a source point set to a target, by
// Gauss-Newton on point-to-point or point-to-plane residuals, reweighted by a robust kernel.
//
// The target is found either through a k-d tree (exact nearest neighbours) or through a
// DistanceField's closest-point grid (O(1) per query, approximate within a voxel). A k-d tree
// target is thread-safe: any number of ICP runs may share one. A distance-field target owns a
// grid sampler and is not: build one per thread, over one shared field.

#include <Eigen/Geometry>
#include <limits>
#include <vector>

#include "lmk/geometry/kdtree.h"
#include "lmk/geometry/point_cloud.h"
#include "lmk/occupancy/distance_field.h"
#include "lmk/registration/registration_result.h"
#include "lmk/registration/robust_loss.h"

namespace lmk {

enum class IcpMode { point_to_point, point_to_plane };

/// Which pairs a registration aligns: each source point with its nearest target point within
/// max_distance, weighted by the robust loss of its residual.
struct Correspondences {
  double max_distance = std::numeric_limits<double>::infinity();  ///< m
  RobustLoss loss;                                                ///< none by default
};

/// When a registration stops: after max_iterations steps, or once a step moves the source by less
/// than both tolerances (converged).
struct Termination {
  int max_iterations = 30;
  double translation_tolerance = 1e-5;  ///< m
  double rotation_tolerance = 1e-5;     ///< rad
};

struct IcpSettings {
  IcpMode mode = IcpMode::point_to_plane;
  Correspondences correspondences;
  Termination termination;
  /// After the last step, one more pass over the correspondences measures `inliers` and
  /// `final_error` at the returned pose. A caller that reads neither (the fast search's alignments,
  /// which score with their own metric) saves that pass, a tenth to a half of a short run.
  bool measure_final = true;
};

/// What ICP aligns to: the nearest target point of a query, with its normal.
class IcpTarget {
 public:
  virtual ~IcpTarget() = default;
  /// False when there is no target point (empty target, or beyond a distance field's band).
  virtual bool nearest(const Eigen::Vector3f& query, Eigen::Vector3f& point,
                       Eigen::Vector3f& normal) const = 0;
  virtual bool has_normals() const = 0;
  /// nearest() for each query in turn: `found[k]` says whether `points[k]` (and `normals[k]`, with
  /// normals) hold its answer. A target whose lookups are independent memory reads overrides it:
  /// issued together they overlap, where one lookup per ICP step waited for each in turn.
  virtual void nearest_all(const std::vector<Eigen::Vector3f>& queries,
                           std::vector<Eigen::Vector3f>& points,
                           std::vector<Eigen::Vector3f>& normals, std::vector<char>& found) const;
};

/// Exact nearest neighbours. `cloud` and `tree` must outlive the target; normals are optional.
class KdTreeTarget : public IcpTarget {
 public:
  KdTreeTarget(const PointCloud& cloud, const KdTree& tree) : cloud_(cloud), tree_(tree) {}
  bool nearest(const Eigen::Vector3f& query, Eigen::Vector3f& point,
               Eigen::Vector3f& normal) const override;
  bool has_normals() const override { return cloud_.has_normals(); }

 private:
  const PointCloud& cloud_;
  const KdTree& tree_;
};

/// Closest points through a distance field's closest-point grid. `normals`, when given, are those
/// of field.points(), index for index. Not thread-safe itself (it owns a grid sampler): build one
/// per thread; the field may be shared.
class DistanceFieldTarget : public IcpTarget {
 public:
  DistanceFieldTarget(const DistanceField& field, const std::vector<Eigen::Vector3f>* normals)
      : field_(field), sampler_(field), normals_(normals) {}
  bool nearest(const Eigen::Vector3f& query, Eigen::Vector3f& point,
               Eigen::Vector3f& normal) const override;
  bool has_normals() const override { return normals_ != nullptr; }
  void nearest_all(const std::vector<Eigen::Vector3f>& queries,
                   std::vector<Eigen::Vector3f>& points, std::vector<Eigen::Vector3f>& normals,
                   std::vector<char>& found) const override;

 private:
  const DistanceField& field_;
  DistanceField::Sampler sampler_;
  const std::vector<Eigen::Vector3f>* normals_;
  mutable std::vector<int> indices_;  // nearest_all's scratch: the target is per thread already
};

/// Aligns `source` (points, and for point-to-plane nothing more: the target's normals are used)
/// to `target`, starting from `T_target_source`. Throws lmk::Error for bad settings, or for
/// point-to-plane against a target without normals.
IcpResult icp(const std::vector<Eigen::Vector3f>& source, const IcpTarget& target,
              const Eigen::Isometry3d& T_target_source, const IcpSettings& settings = {});

}  // namespace lmk
