// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The paper's 17 evaluation scenes (its Tables I-III, docs/datasets.md, "The synthetic benchmark")
// as seeded generators over the object library, with exact ground truth: every landmark instance's
// box in the world frame.
//
// Worlds are z up, in metres, with the floor at z = 0. A seed varies object positions and yaws,
// clutter and the sensor's viewpoint; `hard` adds what the paper's method could not handle: larger
// yaw of the objects, rotated chairs, tilted walls and cabinets, and a rolled camera.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/geometry/point_cloud.h"
#include "lmk/geometry/symmetry.h"
#include "lmk/sim/mesh.h"

namespace lmk {

/// A landmark of the benchmark: cut once, in its demonstration scene, from one object part.
struct BenchmarkLandmark {
  std::string name;        ///< e.g. "bowl_rim"
  std::string setting;     ///< the setting whose scenes it was made for
  std::string demo_scene;  ///< the scene type it is captured in (with seed 0, not hard)
  Symmetry symmetry;       ///< in the landmark's box frame
};

/// The benchmark's landmarks, in a fixed order.
const std::vector<BenchmarkLandmark>& benchmark_landmarks();

struct GeneratedScene {
  std::string type;                     ///< e.g. "cluttered/shelf"
  std::string setting;                  ///< "simple", "cluttered" or "unconventional"
  TriangleMesh mesh;                    ///< world frame
  Eigen::Isometry3d T_world_sensor;     ///< the sensor's optical frame (z forward, y down)
  std::vector<std::string> in_context;  ///< the landmarks the paper searched in this scene
  /// Ground-truth boxes per landmark name, world frame (landmarks absent from the scene have none).
  std::map<std::string, std::vector<Box>> instances;
  /// The light's gain per channel (DepthSensorSettings::light) where the mesh is painted.
  Eigen::Vector3d light = Eigen::Vector3d::Ones();
  /// The depth camera it is rendered with (sim/sensor_models.h).
  std::string sensor = "kinect";
};

/// The 17 scene types, in the paper's order: "simple/bowl_and_cup", ...
const std::vector<std::string>& scene_types();

/// Colour look-alikes (issue #35), beyond the paper: painted objects of one shape in several
/// colours, lit more or less brightly and warmly than at the demonstration: "colour/cups",
/// "colour/bottles", "colour/cartons".
const std::vector<std::string>& colour_scene_types();
/// Their landmarks, each one colour of one shape: "red_cup", "blue_bottle", "yellow_carton".
const std::vector<BenchmarkLandmark>& colour_landmarks();

/// The scene as its sensor (scene.sensor, sim/sensor_models.h) sees it: exact depth, the ground
/// truth's view, or with `noise` the sensor's noise, from the noise stream `noise_seed`.
PointCloud render_scene(const GeneratedScene& scene, bool noise = false,
                        std::uint64_t noise_seed = 0);

/// Builds scene `type` for `seed`. Deterministic: the same arguments give the same scene. Throws
/// lmk::Error naming the known types for an unknown one.
GeneratedScene make_scene(const std::string& type, std::uint64_t seed, bool hard = false);

}  // namespace lmk
