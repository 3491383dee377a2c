// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The OpenVDB grids behind the occupancy types, for code that stores or inspects them (the .lmk
// file). internal/: shared within lmk, not installed, since it exposes OpenVDB types.

#include <openvdb/openvdb.h>

#include "lmk/occupancy/distance_field.h"
#include "lmk/occupancy/internal/leaf_table.h"

namespace lmk {

struct DistanceField::Grids {
  openvdb::FloatGrid::Ptr distance;  ///< unsigned distance at voxel centres, background = band
  openvdb::Int32Grid::Ptr closest;   ///< index of the nearest point, background = -1
  std::vector<Eigen::Vector3f> points;
  double band = 0.0;
  /// The two grids' leaves by arithmetic, for the samplers' lookups: derived from the grids by
  /// DistanceField (its constructor and from_grids), never stored.
  detail::LeafTable<openvdb::FloatTree> distance_leaves;
  detail::LeafTable<openvdb::Int32Tree> closest_leaves;
};

}  // namespace lmk

#include "lmk/occupancy/empty_space.h"

namespace lmk {

struct EmptySpaceGrid::Grid {
  openvdb::BoolGrid::Ptr grid;           ///< active voxels are observed free
  std::vector<Eigen::Vector3f> centres;  ///< their centres, in the grid's iteration order
};

}  // namespace lmk
