// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Where the fast search's seeds can do any good. Internal.
//
// A landmark always has relief (capture refuses flat and straight ones), and the point-pair
// model leaves coplanar pairs out, so a seed whose surroundings are one plane (a stretch of floor,
// wall or table top) casts no vote. In a room-sized frame such seeds are most of a uniform sample,
// and they crowd out the few that fall on a small landmark. Seeds are therefore drawn from the
// points near relief only: points in or next to a cell whose normals are not all parallel.

#include "lmk/geometry/point_cloud.h"

namespace lmk::detail {

/// The indices of the points of `cloud` (which needs normals) that lie in a cell of side `cell`
/// holding two normals more than `angle` apart, or in one of its 26 neighbours. Points without a
/// finite normal are left out. In index order.
Indices points_near_relief(const PointCloud& cloud, double cell, double angle);

/// Seeds spread evenly over `candidates` (indices into `cloud`): one per occupied cell of side
/// `spacing`, chosen within its cell by `seed`. A uniform random sample leaves gaps as wide as its
/// clumps: with a few seeds per instance, some instances got one seed or none (on the viewpoints
/// preset, a partly hidden ball had one seed within 8 cm against fourteen on its neighbour) and
/// were never voted for. In cell order, so the same whatever the order of `candidates`.
Indices spread_seeds(const PointCloud& cloud, const Indices& candidates, double spacing,
                     std::uint64_t seed);

}  // namespace lmk::detail
