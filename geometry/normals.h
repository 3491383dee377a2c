// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Surface normals by principal component analysis of each point's k nearest neighbours: the normal
// is the eigenvector of the neighbourhood covariance with the smallest eigenvalue, flipped to
// face the sensor, because a depth sensor only sees surfaces that face it.

#include "lmk/geometry/kdtree.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk {

struct NormalSettings {
  int k = 20;  ///< neighbours per point, including the point itself (at least 3)
};

/// Normals for every point of `cloud`, using `tree` built over the same cloud. A normal is NaN
/// where the point is not finite or its neighbourhood is degenerate (fewer than 3 neighbours).
/// Oriented towards cloud.sensor_origin(). Parallel over points; the result does not depend on the
/// thread count.
std::vector<Eigen::Vector3f> estimate_normals(const PointCloud& cloud, const KdTree& tree,
                                              const NormalSettings& settings = {});

/// Convenience: builds a tree and stores the normals in cloud.normals.
void compute_normals(PointCloud& cloud, const NormalSettings& settings = {});

}  // namespace lmk
