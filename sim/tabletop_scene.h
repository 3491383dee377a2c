// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A seeded tabletop scene for the built-in demo and for tests that need a realistic frame: a table
// with a carton, a cup and a ball, seen by the simulated Kinect from a robot-like head height.
// The full object library and the paper's 17 scene types build on the same pieces (eval/).

#include <cstdint>
#include <string>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/sim/depth_sensor.h"

namespace lmk {

struct SceneObject {
  std::string name;
  Box box;  ///< the object's bounding box in the world frame: its ground-truth pose and size
};

struct SyntheticScene {
  TriangleMesh mesh;                 ///< world frame, z up, table top at z = table_height
  std::vector<SceneObject> objects;  ///< the objects on the table (not the table itself)
  Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
};

/// Object positions, yaws and the sensor's viewpoint vary with `seed`; the same seed always gives
/// the same scene.
SyntheticScene make_tabletop_scene(std::uint64_t seed);

}  // namespace lmk
