// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The synthetic benchmark as a dataset on disk (docs/datasets.md): the paper's 17 scene types
// rendered by the simulated Kinect for a run of seeds, and its 11 landmarks, each captured once in
// its demonstration scene with the box a user would draw, as the paper's users did.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lmk/datasets/dataset.h"
#include "lmk/datasets/shard.h"
#include "lmk/landmark/landmark.h"
#include "lmk/sim/scene_types.h"

namespace lmk {

/// Bumped whenever the generator's output changes (objects, scene types, sensor, capture), so that
/// cached benchmark datasets are regenerated.
// 3: the Kinect model of lmk sensor-check; 4: the viewpoints and occlusion presets; 5: landmarks'
// empty space stops beside unobserved space (occupancy/empty_space.h); 6: the capture check's
// findings in every landmark, scenes rendered by the preset's sensor model (issue #59)
inline constexpr int kBenchmarkGeneratorVersion = 6;

/// What a preset changes in the generated scenes (sim/scene_variations.h).
enum class SceneVariation {
  none,
  viewpoints,  ///< each scene seen from a random place 0.7-3.5 m from its first landmark instance
  occlusion,   ///< boxes touching or in front of each in-context instance hide 0-60% of it
};

/// A named recipe for a benchmark dataset.
struct BenchmarkPreset {
  std::string name;
  std::string description;
  int seeds = 1;      ///< scenes per scene type
  bool hard = false;  ///< strong rotations and tilts (make_scene's hard variants)
  SceneVariation variation = SceneVariation::none;
  /// The colour look-alikes (colour_scene_types(), colour_landmarks()) instead of the paper's.
  bool colour = false;
  /// The depth camera every scene and landmark is rendered with (sim/sensor_models.h); with
  /// SceneVariation::viewpoints, seen from that camera's own ranges (SensorModel::min_range,
  /// max_range), and demonstrated from within them.
  std::string sensor = "kinect";
};

/// "paper" (the 17 types, one seed each), "paper-x10" (ten seeds each), "rotations" (the hard
/// variants, three seeds each), "viewpoints" (six seeds each, seen from new places) and
/// "occlusion" (four seeds each, with occluders); and "colours" (the colour look-alikes, eight
/// seeds each).
const std::vector<BenchmarkPreset>& benchmark_presets();
/// The preset called `name`; throws lmk::Error listing the known ones otherwise.
const BenchmarkPreset& benchmark_preset(const std::string& name);

/// The most scenes per scene type a benchmark may have: 1000 x 17 types is 17,000 renders (hours
/// on 2 cores and about 40 GB of scenes); the presets use 1 to 10. Checked before any work: a
/// million asked for 2.5 GB before any output (issue #47).
inline constexpr int kMaxSeedsPerType = 1000;

struct GenerateOptions {
  std::optional<int> seeds;  ///< scenes per type instead of the preset's (1 to kMaxSeedsPerType)
  bool hard = false;         ///< hard variants even where the preset has none
  std::uint64_t first_seed = 1;  ///< seeds first_seed, first_seed + 1, ...; 0 is the demo scene
  bool noise = true;             ///< false renders exact depth (for ground-truth checks)
  /// Only these scene types (and the landmarks in context in them); empty: every type and every
  /// landmark.
  std::vector<std::string> types;
  /// Only this shard's scenes (scene_shard() of their names); every shard writes the landmarks.
  /// The dataset's dataset.json comes from a run with `merge` once every shard has run.
  std::optional<Shard> shard;
  /// Render nothing: gather the scenes the shards wrote into dataset.json, or fail naming those
  /// still missing.
  bool merge = false;
  /// Each landmark is also captured from 2 up to this many demonstration views (issue #35): its
  /// demonstration camera, then that camera turned about the vertical through the instance by
  /// +45, -45 and +90 degrees; the landmark of k views is "<name>-v<k>", with the same pairs.
  int views = 1;
  /// Each scene fused from this many renders of it (issue #46; occupancy/tsdf_volume.h), each with
  /// its own noise, the k-th from the scene's camera panned by head_turn degrees times 0, +1, -1,
  /// +2, -2, ... about the vertical through it (a robot's head turning between looks). 1 renders
  /// one frame as before.
  int frames = 1;
  double head_turn = 0.0;  ///< degrees
  /// Called after each file written, with (files done, files in all).
  std::function<void(std::size_t, std::size_t)> progress;
};

/// What a generation did: the dataset, complete unless a shard ran, and what this run wrote.
struct Generated {
  Dataset dataset;           ///< a shard's: its own scenes only, and no dataset.json written
  std::size_t rendered = 0;  ///< scenes rendered by this run
  std::size_t kept = 0;      ///< scenes of this run found already rendered (a rerun resumes)
};

/// Landmark `landmark` captured in its demonstration scene (its demo_scene type, seed 0, not
/// hard), in the world frame (z up), with the box of the scene's first instance of it; with
/// `views` above 1, fused from that many demonstration views (GenerateOptions::views). With a
/// `sensor` other than the Kinect (sim/sensor_models.h), rendered by it, the camera moved along
/// its line of sight to the box into that sensor's range.
Landmark capture_benchmark_landmark(const BenchmarkLandmark& landmark, bool noise = true,
                                    int views = 1, const std::string& sensor = "kinect");

/// The dataset scene name for a scene type and seed: "simple-bowl_and_cup-3", "...-3-hard", and
/// with a variation "...-3-viewpoints", "...-3-occlusion".
std::string benchmark_scene_name(const std::string& type, std::uint64_t seed, bool hard,
                                 SceneVariation variation = SceneVariation::none);

/// Writes the preset into `dir` (created if absent): landmarks/NAME.lmk, scenes/NAME.pcd (organised
/// 640x480 frames in the world frame, the sensor pose in the PCD VIEWPOINT) and dataset.json,
/// which lists for every scene its in-context landmarks and every landmark it holds an instance
/// of. The same preset and options always write the same content, sharded or not: each scene is
/// written with its dataset entry beside it (in a parts directory of `dir` named after the preset
/// and options) and found there by a rerun, which renders only what is missing.
Dataset generate_benchmark_dataset(const std::string& dir, const std::string& preset,
                                   const GenerateOptions& options = {});
/// The same, saying what this run rendered and what it found done.
Generated generate_benchmark(const std::string& dir, const std::string& preset,
                             const GenerateOptions& options = {});

/// Where an evaluation keeps a preset's generated dataset: `cache_dir`, or without a cache (empty)
/// the system's temporary directory's lmk-datasets, out of the user's way. What `lmk eval`, `lmk
/// ablate` and Python's lmk.eval share.
std::string benchmark_dataset_home(const std::string& cache_dir);

/// The preset's dataset under CACHE_DIR/datasets/, generated there first if it is not yet (into a
/// temporary directory renamed into place, so an interrupted generation leaves nothing half
/// written). Returns its directory.
std::string cached_benchmark_dataset(const std::string& cache_dir, const std::string& preset,
                                     const GenerateOptions& options = {});

}  // namespace lmk
