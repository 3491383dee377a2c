// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Where the fast search's seeds can do any good. Internal.
//
// A landmark always has relief (capture refuses flat and straight ones), and the point-pair
// model leaves coplanar pairs out, so a seed whose surroundings are one plane (a stretch of floor,
// wall or table top) casts no vote. In a room-sized frame such seeds are most of a uniform sample,
// and they crowd out the few that fall on a small landmark. Seeds are therefore drawn from the
// points near relief only: points in or next to a cell whose normals are not all parallel and whose
// points stand further off one plane than the sensor's depth noise explains.
//
// The second test is what keeps a room-sized frame cheap. At 2-3 m a Kinect's depth levels are
// 2 cm apart and its noise is about 1 cm, so normals pooled over two coarse leaves scatter on a
// bare floor or wall as they would on relief: 82% of a synthetic shelf frame's points passed the
// normal test alone, and their seeds were most of the search's cost (docs/cluster.md).

#include <Eigen/Geometry>
#include <optional>

#include "lmk/geometry/depth_noise.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk::detail {

/// What makes a cell of the scene relief.
struct ReliefTest {
  double cell = 0.1;    ///< side of the cells, m
  double angle = 0.26;  ///< two normals of the cell more than this apart, rad
  /// The sensor that measured the cloud (cloud frame) and its noise: a cell's points must also
  /// stand off their best plane by more than one measurement sigma at the cell's depth. Without a
  /// sensor the normals alone decide.
  std::optional<Eigen::Isometry3d> T_cloud_sensor;
  DepthNoise noise;
};

/// The indices of the points of `cloud` (which needs normals) that lie in a relief cell or in one
/// of its 26 neighbours. Points without a finite normal are left out. In index order.
Indices points_near_relief(const PointCloud& cloud, const ReliefTest& test);

/// Seeds spread evenly over `candidates` (indices into `cloud`): one per occupied cell of side
/// `spacing`, chosen within its cell by `seed`. A uniform random sample leaves gaps as wide as its
/// clumps: with a few seeds per instance, some instances got one seed or none (on the viewpoints
/// preset, a partly hidden ball had one seed within 8 cm against fourteen on its neighbour) and
/// were never voted for. In cell order, so the same whatever the order of `candidates`.
Indices spread_seeds(const PointCloud& cloud, const Indices& candidates, double spacing,
                     std::uint64_t seed);

}  // namespace lmk::detail
