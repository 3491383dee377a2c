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

}  // namespace lmk
