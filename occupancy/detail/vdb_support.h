// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// OpenVDB set-up shared by the occupancy types. Internal.

#include <openvdb/openvdb.h>

#include <Eigen/Core>
#include <cmath>

namespace lmk::detail {

/// openvdb::initialize(), once per process (it registers grid types for I/O; thread-safe).
void initialize_openvdb();

/// The integer nearest to `v`, halves rounded up, inline: grid lookups call it three times each,
/// and std::lround is an out-of-line libm call that showed in the fast search's profile.
inline int round_to_int(double v) {
  const double shifted = v + 0.5;
  const int truncated = static_cast<int>(shifted);
  return truncated - (shifted < static_cast<double>(truncated) ? 1 : 0);  // floor
}

/// The voxel coordinate whose centre is nearest to `p` on a grid of side `voxel` anchored at the
/// origin (OpenVDB's cell-centred convention).
inline openvdb::Coord nearest_voxel(const Eigen::Vector3d& p, double voxel) {
  return openvdb::Coord(round_to_int(p.x() / voxel), round_to_int(p.y() / voxel),
                        round_to_int(p.z() / voxel));
}

}  // namespace lmk::detail
