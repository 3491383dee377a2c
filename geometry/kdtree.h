// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// KdTree: nearest-neighbour queries over the finite points of a PointCloud (nanoflann).
//
// Lifetime: the tree copies the points it indexes, so it stays valid after the cloud is changed
// or destroyed. Indices in results refer to positions in the cloud the tree was built from (NaN
// points are skipped, never returned).
// Thread safety: after construction every query is const and keeps no shared scratch state, so
// any number of threads may query one tree concurrently.

#include <memory>
#include <optional>
#include <vector>

#include "lmk/geometry/point_cloud.h"

namespace lmk {

struct Neighbor {
  Index index;             ///< index of the point in the source cloud
  float squared_distance;  ///< squared Euclidean distance to the query, m^2
};

class KdTree {
 public:
  /// Builds the tree over the finite points of `cloud`. `leaf_max_size` trades build time against
  /// query time (nanoflann's default is 10).
  explicit KdTree(const PointCloud& cloud, int leaf_max_size = 10);
  ~KdTree();
  KdTree(KdTree&&) noexcept;
  KdTree& operator=(KdTree&&) noexcept;

  /// Number of indexed (finite) points.
  std::size_t size() const;

  /// The k nearest points, closest first; fewer when the tree holds fewer than k points.
  std::vector<Neighbor> knn(const Eigen::Vector3f& query, std::size_t k) const;
  /// Allocation-free form for hot loops: fills `out` (resized to the number found).
  void knn(const Eigen::Vector3f& query, std::size_t k, std::vector<Neighbor>& out) const;
  /// The nearest point, or nothing when the tree is empty.
  std::optional<Neighbor> nearest(const Eigen::Vector3f& query) const;
  /// Every point strictly closer than `radius` (metres), closest first.
  std::vector<Neighbor> radius(const Eigen::Vector3f& query, float radius) const;
  /// The same points in no particular order (faster: no sort), into `out`.
  void radius_unsorted(const Eigen::Vector3f& query, float radius,
                       std::vector<Neighbor>& out) const;

 private:
  void radius_search(const Eigen::Vector3f& query, float radius, bool sorted,
                     std::vector<Neighbor>& out) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lmk
