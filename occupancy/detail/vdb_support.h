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
/// and std::lround is an out-of-line libm call that showed in the fast search's profile. Inlined
/// by force, as nearest_voxel below: in a unity build's large translation unit GCC's inlining
/// budget ran out, and the closest-point lookups called nearest_voxel out of line (5% of a
/// bench search's samples).
[[gnu::always_inline]] inline int round_to_int(double v) {
  const double shifted = v + 0.5;
  const int truncated = static_cast<int>(shifted);
  return truncated - (shifted < static_cast<double>(truncated) ? 1 : 0);  // floor
}

/// The voxel coordinate whose centre is nearest to `p` on a grid of side 1 / `inverse_voxel`
/// anchored at the origin (OpenVDB's cell-centred convention). The inverse, not the side: the
/// lookups run millions of times per search, and a multiplication costs a fraction of a division.
[[gnu::always_inline]] inline openvdb::Coord nearest_voxel(const Eigen::Vector3d& p,
                                                           double inverse_voxel) {
  return openvdb::Coord(round_to_int(p.x() * inverse_voxel), round_to_int(p.y() * inverse_voxel),
                        round_to_int(p.z() * inverse_voxel));
}

}  // namespace lmk::detail
