#pragma once
// OpenVDB set-up shared by the occupancy types. Internal.

#include <openvdb/openvdb.h>

#include <Eigen/Core>
#include <cmath>

namespace lmk::detail {

/// openvdb::initialize(), once per process (it registers grid types for I/O; thread-safe).
void initialize_openvdb();

/// The voxel coordinate whose centre is nearest to `p` on a grid of side `voxel` anchored at the
/// origin (OpenVDB's cell-centred convention).
inline openvdb::Coord nearest_voxel(const Eigen::Vector3d& p, double voxel) {
  return openvdb::Coord(static_cast<int>(std::lround(p.x() / voxel)),
                        static_cast<int>(std::lround(p.y() / voxel)),
                        static_cast<int>(std::lround(p.z() / voxel)));
}

}  // namespace lmk::detail
