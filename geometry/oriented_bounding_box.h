// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Oriented bounding box of a cloud: the box of (approximately) smallest volume that holds every
// finite point, from CGAL's Optimal_bounding_box (Chang, Gorissen & Melchior 2011). It is the
// seed of the automatic first guess of a landmark box that the paper's users asked for.

#include "lmk/geometry/box.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk {

struct OrientedBoundingBoxSettings {
  /// Seed of CGAL's evolutionary search, so that the same cloud always gives the same box.
  unsigned int seed = 0;
};

/// Throws lmk::Error when the cloud has fewer than 4 finite points.
Box oriented_bounding_box(const PointCloud& cloud,
                          const OrientedBoundingBoxSettings& settings = {});

/// The smallest box standing on the plane n.x + d = 0 (`plane`, n of unit length) that holds every
/// finite point: its base is the minimum-area rectangle of the points' footprint on the plane
/// (CGAL's min_rectangle_2 over their convex hull), its height the farthest point's distance
/// above the plane, and its z axis n. An object on a table gets an upright box resting on the
/// table, whatever its shape. Throws lmk::Error for fewer than 3 finite points or a point below
/// the plane by more than 1 cm.
Box upright_bounding_box(const PointCloud& cloud, const Eigen::Vector4d& plane);

}  // namespace lmk
