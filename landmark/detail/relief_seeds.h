#pragma once
// Where the fast search's seeds can do any good. Internal.
//
// A landmark always has relief (capture refuses flat and straight ones), and the point-pair
// model leaves coplanar pairs out, so a seed whose surroundings are one plane (a stretch of floor,
// wall or table top) casts no vote. In a room-sized frame such seeds are most of a uniform sample,
// and they crowd out the few that fall on a small landmark. Seeds are therefore drawn from the
// points near relief only: points in or next to a cell whose normals are not all parallel.

#include "geometry/point_cloud.h"

namespace lmk::detail {

/// The indices of the points of `cloud` (which needs normals) that lie in a cell of side `cell`
/// holding two normals more than `angle` apart, or in one of its 26 neighbours. Points without a
/// finite normal are left out. In index order.
Indices points_near_relief(const PointCloud& cloud, double cell, double angle);

}  // namespace lmk::detail
