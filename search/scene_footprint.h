// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What indexing a scene and searching it will take at its peak, estimated from the scene's points
// without building anything (issue #47). `lmk serve` admits a search only when this fits what is
// left of its memory budget; `lmk find` refuses a scene that would not fit the machine.
//
// The peak is not a function of the point count alone: the distance field covers a band around
// every coarse voxel, so 5 million points on a room's surfaces index in 0.45 GB, the same points
// scattered through a 3 m cube in 1.3 GB, and scattered through a 100 m cube in over 24 GB.
// The estimate therefore counts what the index will hold: the finite points in the work volume,
// the occupied coarse voxels, and the OpenVDB leaf nodes of the occupancy grid and of the field's
// band. Each is priced by what it costs in SceneIndex (measured; tests/landmark/
// scene_footprint_test.cpp holds the estimate against the measured peak).
#include <cstddef>
#include <limits>
#include <string>

#include "lmk/geometry/point_cloud.h"
#include "lmk/landmark/scene_settings.h"

namespace lmk {

struct SceneFootprint {
  std::size_t points = 0;           ///< finite points in the work volume
  std::size_t coarse_voxels = 0;    ///< occupied voxels of the coarse leaf
  std::size_t occupancy_nodes = 0;  ///< leaf nodes (8^3 voxels) of the occupancy grid
  std::size_t field_nodes = 0;      ///< leaf nodes of the distance field's band, as far as counted
  /// The counting stopped once the estimate passed the caller's limit: `bytes` is then a lower
  /// bound, already over the limit.
  bool over_limit = false;
  std::size_t bytes = 0;  ///< the estimated peak of SceneIndex and a search in it, bytes
};

/// The peak memory of `SceneIndex(scene, settings)` and of a search in it (the lazily built fine
/// level included), from one pass over the points: about 8 bytes per point and 24 per field node
/// while it counts, and a fraction of a second per million points. Counting stops as soon as the
/// estimate passes `limit`, so that a hostile scene costs no more to refuse than a small one.
/// Throws lmk::Error for bad settings, as SceneIndex does.
SceneFootprint estimate_scene_footprint(
    const PointCloud& scene, const SceneSettings& settings,
    std::size_t limit = std::numeric_limits<std::size_t>::max());

/// The memory this machine can give now: /proc/meminfo's MemAvailable (SIZE_MAX when unknown).
std::size_t available_memory();

/// Throws lmk::Error, one line saying what the scene needs and what to change, when indexing and
/// searching `scene` would take more than available_memory(): such a scene is refused before
/// anything is built instead of being killed by the kernel (points scattered through a 100 m cube
/// took over 24 GB). A pass over the points: about 10 ms for a Kinect frame.
void require_footprint_fits(const PointCloud& scene, const SceneSettings& settings);

/// "0.45 GB", "120 MB": a byte count as users read it.
std::string describe_bytes(std::size_t bytes);

}  // namespace lmk
