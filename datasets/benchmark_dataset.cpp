// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/datasets/benchmark_dataset.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>

#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/hash.h"
#include "lmk/geometry/input_file.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/version.h"
#include "lmk/landmark/capture_views.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/occupancy/tsdf_volume.h"
#include "lmk/search/capture_check.h"
#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/instance_visibility.h"
#include "lmk/sim/scene_variations.h"
#include "lmk/sim/sensor_models.h"

namespace lmk {

namespace fs = std::filesystem;

namespace {

// The scene fused from options.frames renders (GenerateOptions::frames): each with its own noise,
// the k-th from the camera panned by head_turn x (0, +1, -1, +2, -2, ...) about the vertical
// through it; fused into the first render's view.
PointCloud render_fused(GeneratedScene scene, const GenerateOptions& options, std::uint64_t seed) {
  const Eigen::Isometry3d camera = scene.T_world_sensor;
  std::vector<PointCloud> renders;
  for (int k = 0; k < options.frames; ++k) {
    const double pan = alternating_step(k) * options.head_turn * M_PI / 180.0;
    Eigen::Isometry3d turned = camera;
    turned.linear() = Eigen::AngleAxisd(pan, Eigen::Vector3d::UnitZ()) * camera.linear();
    scene.T_world_sensor = turned;
    renders.push_back(render_scene(scene, options.noise, seed + static_cast<std::uint64_t>(k)));
  }
  std::vector<DepthFrame> frames;
  for (const PointCloud& r : renders) frames.push_back({&r});
  return fuse_frames(frames);
}

// Each rendered frame gets its own noise stream, derived from what the frame shows.
std::uint64_t noise_seed(const std::string& scene_name) {
  return fnv1a(scene_name.data(), scene_name.size());
}

// The scene's ground truth as dataset pairs: its in-context landmarks, and any other landmark it
// holds an instance of (out of context, yet a correct find there is no false positive), each
// instance with the fraction of the landmark the scene's sensor does not see in `exact` (the frame
// without noise).
std::vector<DatasetPair> pairs_of(const GeneratedScene& scene,
                                  const std::vector<BenchmarkLandmark>& landmarks,
                                  const std::map<std::string, Landmark>& captured,
                                  const PointCloud& exact) {
  std::vector<DatasetPair> pairs;
  for (const BenchmarkLandmark& landmark : landmarks) {
    const bool in_context = std::find(scene.in_context.begin(), scene.in_context.end(),
                                      landmark.name) != scene.in_context.end();
    const auto it = scene.instances.find(landmark.name);
    const bool has_instances = it != scene.instances.end() && !it->second.empty();
    if (!in_context && !has_instances) continue;
    DatasetPair pair{landmark.name, in_context, {}, {}, std::nullopt};
    if (has_instances) {
      const auto model = captured.find(landmark.name);
      for (const Box& box : it->second) {
        pair.instances.push_back(box.pose);
        if (model != captured.end())
          pair.hidden.push_back(
              hidden_fraction(model->second, box, exact, sensor_model(scene.sensor).settings));
      }
    }
    pairs.push_back(pair);
  }
  return pairs;
}

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += n + ";";
  return out;
}

// What decides a generated dataset's content: the preset and the options (not the shard).
std::string generation_key(const std::string& preset, const GenerateOptions& options) {
  Fnv1a key;
  key.add(preset)
      .add_value(options.seeds.value_or(0))
      .add_value(options.hard)
      .add_value(options.first_seed)
      .add_value(options.noise)
      .add(join(options.types));
  if (options.views > 1) key.add_value(options.views);  // one view: the key it always had
  if (options.frames > 1) key.add_value(options.frames).add_value(options.head_turn);
  return key.add_value(kBenchmarkGeneratorVersion).add(kVersion).hex();
}

}  // namespace

const std::vector<BenchmarkPreset>& benchmark_presets() {
  static const std::vector<BenchmarkPreset> all = {
      {"paper", "the paper's 17 scene types, one scene each", 1, false},
      {"paper-x10", "the paper's 17 scene types, ten scenes each", 10, false},
      // Cluster scale (docs/cluster.md): 1,700 scenes, about 2,700 in-context pairs.
      {"paper-x100", "the paper's 17 scene types, a hundred scenes each", 100, false},
      {"rotations", "the 17 scene types with strong rotations and tilts, three scenes each", 3,
       true},
      {"viewpoints",
       "the 17 scene types seen from 0.7-3.5 m, within 60 degrees of the demonstration's side and "
       "0.8-1.8 m high, six scenes each",
       6, false, SceneVariation::viewpoints},
      {"occlusion",
       "the 17 scene types with boxes touching or in front of each landmark instance, hiding 0-60% "
       "of it, four scenes each",
       4, false, SceneVariation::occlusion},
      {"colours",
       "colour look-alikes: cups, bottles and cartons of one shape in several colours, under "
       "lights 0.6-1.3 times as bright as the demonstration's, eight scenes each",
       8, false, SceneVariation::none, true},
      // Issue #59: the same worlds through other kinds of depth camera, each from its own ranges
      // (sim/sensor_models.h), for a confidence that means the same on every sensor.
      {"realsense",
       "the 17 scene types through an active-stereo camera (RealSense-like), seen from 0.4-1.5 m "
       "and demonstrated from within 1.5 m, three scenes each",
       3, false, SceneVariation::viewpoints, false, "realsense"},
      {"tof",
       "the 17 scene types through a time-of-flight camera (Kinect v2-like), seen from 0.6-3 m, "
       "three scenes each",
       3, false, SceneVariation::viewpoints, false, "tof"},
  };
  return all;
}

const BenchmarkPreset& benchmark_preset(const std::string& name) {
  std::string known;
  for (const BenchmarkPreset& preset : benchmark_presets()) {
    if (preset.name == name) return preset;
    known += (known.empty() ? "" : ", ") + preset.name;
  }
  throw Error("unknown preset '" + name + "' (known: " + known + ")");
}

// The demonstration camera of `scene` moved along its line of sight to `target` into the range
// `sensor` works at (the Kinect keeps the scene's own camera): the same view of the landmark, as
// near as that camera must be, and no nearer (a box seen closer leaves the image).
void demonstrate_from(GeneratedScene& scene, const std::string& sensor,
                      const Eigen::Vector3d& target) {
  scene.sensor = sensor;
  if (sensor == "kinect") return;
  const SensorModel& model = sensor_model(sensor);
  const Eigen::Vector3d from = scene.T_world_sensor.translation();
  const double range = std::clamp((from - target).norm(), model.min_range, model.max_range);
  scene.T_world_sensor.translation() = target + (from - target).normalized() * range;
}

Landmark capture_benchmark_landmark(const BenchmarkLandmark& landmark, bool noise, int views,
                                    const std::string& sensor) {
  GeneratedScene demo = make_scene(landmark.demo_scene, 0, false);
  const auto it = demo.instances.find(landmark.name);
  if (it == demo.instances.end() || it->second.empty()) {
    throw Error("landmark '" + landmark.name + "' has no instance in its demonstration scene " +
                landmark.demo_scene);
  }
  if (views < 1 || views > 4) throw Error("a benchmark landmark takes 1 to 4 views");
  const Box& box = it->second.front();
  demonstrate_from(demo, sensor, box.center());
  const std::string demo_name = benchmark_scene_name(landmark.demo_scene, 0, false);
  // The demonstration camera, then turned about the vertical through the instance: the viewpoints
  // preset searches from within 60 degrees of the demonstration's side.
  const double turns[] = {0.0, M_PI / 4.0, -M_PI / 4.0, M_PI / 2.0};
  const Eigen::Isometry3d first = demo.T_world_sensor;
  std::vector<PointCloud> clouds;
  for (int v = 0; v < views; ++v) {
    Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
    turn.translate(box.center())
        .rotate(Eigen::AngleAxisd(turns[v], Eigen::Vector3d::UnitZ()))
        .translate(-box.center());
    demo.T_world_sensor = turn * first;
    clouds.push_back(render_scene(
        demo, noise, noise_seed(v == 0 ? demo_name : demo_name + "-view" + std::to_string(v))));
  }
  CaptureSettings settings;
  settings.base_frame = true;  // the world frame: z up
  Landmark captured;
  if (views == 1) {
    captured = capture(clouds.front(), box, landmark.name, settings);
  } else {
    std::vector<CaptureView> placed;  // every render is in the world frame
    for (const PointCloud& cloud : clouds)
      placed.push_back({&cloud, Eigen::Isometry3d::Identity()});
    captured = capture_views(
        placed, box, views_landmark_name(landmark.name, static_cast<std::size_t>(views)), settings);
  }
  // The capture check in the demonstration's render, as `lmk capture` runs it (issue #59): its
  // findings travel with the landmark into every match's confidence.
  FindSettings check;
  check.scene.up = captured.up;
  captured.findings = check_capture(captured, &clouds.front(), check).findings;
  return captured;
}

std::string benchmark_scene_name(const std::string& type, std::uint64_t seed, bool hard,
                                 SceneVariation variation) {
  std::string name = type;
  std::replace(name.begin(), name.end(), '/', '-');
  name += "-" + std::to_string(seed) + (hard ? "-hard" : "");
  if (variation == SceneVariation::viewpoints) name += "-viewpoints";
  if (variation == SceneVariation::occlusion) name += "-occlusion";
  return name;
}

namespace {

// The options a generation can run with (`seeds` resolved from the preset); lmk::Error naming the
// first that is not.
void check_generate_options(const GenerateOptions& options, int seeds) {
  if (seeds < 1 || seeds > kMaxSeedsPerType) {
    throw Error("--seeds must be 1 to " + std::to_string(kMaxSeedsPerType) + " (got " +
                std::to_string(seeds) + ")");
  }
  if (options.merge && options.shard)
    throw Error("gen: a merge gathers every shard; give no shard");
  if (options.frames < 1 || static_cast<std::size_t>(options.frames) > kMaxFusedFrames) {
    throw Error("gen: --frames " + std::to_string(options.frames) + ": must be 1 to " +
                std::to_string(kMaxFusedFrames));
  }
  if (!(options.head_turn >= 0.0 && options.head_turn <= 45.0))
    throw Error("gen: --head-turn " + std::to_string(options.head_turn) +
                ": must be 0 to 45 degrees");
  if (options.views < 1 || options.views > 4) throw Error("gen: --views must be 1 to 4");
}

// The landmarks the scenes of `types` hold in context, in the libraries' order.
std::vector<BenchmarkLandmark> landmarks_of(const std::vector<std::string>& types) {
  std::set<std::string> wanted;
  for (const std::string& type : types) {
    for (const std::string& name : make_scene(type, 0, false).in_context)  // unknown types throw
      wanted.insert(name);
  }
  std::vector<BenchmarkLandmark> landmarks;
  for (const auto* list : {&benchmark_landmarks(), &colour_landmarks()}) {
    for (const BenchmarkLandmark& l : *list) {
      if (wanted.count(l.name)) landmarks.push_back(l);
    }
  }
  return landmarks;
}

// A scene of the dataset: its type, name and seed.
struct PlannedScene {
  std::string type, name;
  std::uint64_t seed;
};

// The scenes, in dataset order (`planned`), and those this run renders (`mine`: its shard's, none
// for a merge).
struct ScenePlan {
  std::vector<PlannedScene> planned, mine;
};

ScenePlan plan_scenes(const std::vector<std::string>& types, int seeds, bool hard,
                      const BenchmarkPreset& preset, const GenerateOptions& options) {
  ScenePlan plan;
  for (const std::string& type : types) {
    for (int k = 0; k < seeds; ++k) {
      const std::uint64_t seed = options.first_seed + static_cast<std::uint64_t>(k);
      plan.planned.push_back(
          {type, benchmark_scene_name(type, seed, hard, preset.variation), seed});
      const bool in_shard =
          !options.shard ||
          scene_shard(plan.planned.back().name, options.shard->count) == options.shard->index;
      if (in_shard && !options.merge) plan.mine.push_back(plan.planned.back());
    }
  }
  return plan;
}

// Every landmark in 1 to options.views views, listed in `dataset` and (unless merging) captured
// into `dir`; returns the one-view captures, which the truth and the hidden fractions use. Every
// shard captures them; a capture is deterministic, so whichever shard's file lands last holds the
// same landmark.
std::map<std::string, Landmark> capture_landmarks(const std::vector<BenchmarkLandmark>& landmarks,
                                                  const GenerateOptions& options,
                                                  const std::string& sensor, const std::string& dir,
                                                  Dataset& dataset,
                                                  const std::function<void()>& step) {
  std::map<std::string, Landmark> captured;
  for (const BenchmarkLandmark& landmark : landmarks) {
    for (int views = 1; views <= options.views; ++views) {
      const std::string name = views_landmark_name(landmark.name, static_cast<std::size_t>(views));
      const std::string file = "landmarks/" + name + ".lmk";
      dataset.landmarks.push_back({name, file, landmark.symmetry});
      if (options.merge) continue;
      const Landmark l = capture_benchmark_landmark(landmark, options.noise, views, sensor);
      save_landmark((fs::path(dir) / file).string(), l);
      if (views == 1) captured[landmark.name] = l;
    }
    if (!options.merge) step();
  }
  return captured;
}

// Scene `p` rendered into `dir` with its ground truth; returns its entry's text, as its part
// holds it.
std::string render_benchmark_scene(const PlannedScene& p, const BenchmarkPreset& preset, bool hard,
                                   const std::vector<BenchmarkLandmark>& landmarks,
                                   const std::map<std::string, Landmark>& captured,
                                   const GenerateOptions& options, const std::string& dir) {
  DatasetScene entry;
  entry.name = p.name;
  GeneratedScene scene = make_scene(p.type, p.seed, hard);
  scene.sensor = preset.sensor;
  const std::uint64_t variation_seed = noise_seed(entry.name);
  if (preset.variation == SceneVariation::viewpoints) {
    ViewpointRange range;
    if (preset.sensor != "kinect") {  // the Kinect's presets keep the range they always had
      range.min_range = sensor_model(preset.sensor).min_range;
      range.max_range = sensor_model(preset.sensor).max_range;
    }
    view_from_random_viewpoint(scene, captured, variation_seed, range);
  }
  if (preset.variation == SceneVariation::occlusion) add_occluders(scene, captured, variation_seed);
  entry.file = "scenes/" + entry.name + ".pcd";
  entry.setting = scene.setting;
  entry.T_scene_sensor = scene.T_world_sensor;
  entry.up = Eigen::Vector3d::UnitZ();
  const PointCloud exact = render_scene(scene);
  for (const DatasetPair& pair : pairs_of(scene, landmarks, captured, exact)) {
    // A landmark of several views is searched where its one-view landmark is, for the same
    // instances.
    for (int views = 1; views <= options.views; ++views) {
      entry.pairs.push_back(pair);
      entry.pairs.back().landmark =
          views_landmark_name(pair.landmark, static_cast<std::size_t>(views));
    }
  }
  write_cloud((fs::path(dir) / entry.file).string(),
              options.frames > 1 ? render_fused(scene, options, noise_seed(entry.name))
                                 : render_scene(scene, options.noise, noise_seed(entry.name)));
  return scene_entry_text(entry);
}

// lmk::Error naming (up to ten of) the scenes no shard has rendered yet.
[[noreturn]] void throw_missing_scenes(const std::vector<std::string>& missing,
                                       std::size_t planned) {
  std::string names;
  for (std::size_t k = 0; k < missing.size() && k < 10; ++k) names += (k ? ", " : "") + missing[k];
  if (missing.size() > 10) names += ", ...";
  throw Error("gen merge: " + std::to_string(missing.size()) + " of " + std::to_string(planned) +
              " scenes are not rendered yet (" + names + "): run the shards that hold them");
}

}  // namespace

Generated generate_benchmark(const std::string& dir, const std::string& preset_name,
                             const GenerateOptions& options) {
  const BenchmarkPreset& preset = benchmark_preset(preset_name);
  const int seeds = options.seeds.value_or(preset.seeds);
  check_generate_options(options, seeds);
  const bool hard = preset.hard || options.hard;
  const fs::path parts = fs::path(dir) / (".parts-" + generation_key(preset_name, options));

  std::error_code ec;
  fs::create_directories(fs::path(dir) / "landmarks", ec);
  fs::create_directories(fs::path(dir) / "scenes", ec);
  fs::create_directories(parts, ec);
  if (ec) throw Error(dir + ": cannot create the dataset directory (" + ec.message() + ")");

  const std::vector<std::string>& preset_types =
      preset.colour ? colour_scene_types() : scene_types();
  const std::vector<std::string> types = options.types.empty() ? preset_types : options.types;
  const std::vector<BenchmarkLandmark> landmarks = landmarks_of(types);
  const ScenePlan plan = plan_scenes(types, seeds, hard, preset, options);

  Generated out;
  Dataset& dataset = out.dataset;
  dataset.name = preset.name + (hard && !preset.hard ? "-hard" : "");
  const std::size_t total = (options.merge ? 0 : landmarks.size()) + plan.mine.size();
  std::size_t done = 0;
  const std::function<void()> step = [&] {
    if (options.progress) options.progress(++done, total);
  };
  const std::map<std::string, Landmark> captured =
      capture_landmarks(landmarks, options, preset.sensor, dir, dataset, step);

  // A scene's entry is written after its cloud, so an entry means a complete scene.
  const auto part_of = [&](const std::string& name) { return parts / (name + ".json"); };
  const auto read_part = [&](const std::string& name) {
    const std::string where = part_of(name).string();
    return parse_scene_entry(read_input_file(where, kDatasetInput), where);
  };
  std::map<std::string, DatasetScene> entries;  // this run's scenes, rendered or found done
  for (const PlannedScene& p : plan.mine) {
    if (fs::is_regular_file(part_of(p.name))) {
      entries[p.name] = read_part(p.name);
      ++out.kept;
    } else {
      // Kept as its part holds it: a pose goes through its quaternion there, which is not
      // bit-exact, so a scene rendered now and one a shard rendered must take the same way for
      // dataset.json to be the same whichever ran.
      const std::string text =
          render_benchmark_scene(p, preset, hard, landmarks, captured, options, dir);
      write_text_atomically(part_of(p.name), text);
      entries[p.name] = parse_scene_entry(text, part_of(p.name).string());
      ++out.rendered;
    }
    step();
  }
  if (options.shard) {
    for (const PlannedScene& p : plan.mine) dataset.scenes.push_back(entries[p.name]);
    return out;
  }

  // The whole dataset: every scene's entry, in dataset order, from this run or from the shards'
  // parts, or the names of those missing.
  std::vector<std::string> missing;
  for (const PlannedScene& p : plan.planned) {
    if (const auto it = entries.find(p.name); it != entries.end()) {
      dataset.scenes.push_back(it->second);
    } else if (fs::is_regular_file(part_of(p.name))) {
      dataset.scenes.push_back(read_part(p.name));
    } else {
      missing.push_back(p.name);
    }
  }
  if (!missing.empty()) throw_missing_scenes(missing, plan.planned.size());
  for (const DatasetLandmark& l : dataset.landmarks) {
    if (!fs::is_regular_file(fs::path(dir) / l.file))
      throw Error("gen merge: " + (fs::path(dir) / l.file).string() + " is missing: run a shard");
  }
  save_dataset(dir, dataset);
  fs::remove_all(parts, ec);  // the dataset is complete: dataset.json holds every entry
  return out;
}

Dataset generate_benchmark_dataset(const std::string& dir, const std::string& preset,
                                   const GenerateOptions& options) {
  return generate_benchmark(dir, preset, options).dataset;
}

std::string benchmark_dataset_home(const std::string& cache_dir) {
  return cache_dir.empty() ? (fs::temp_directory_path() / "lmk-datasets").string() : cache_dir;
}

std::string cached_benchmark_dataset(const std::string& cache_dir, const std::string& preset,
                                     const GenerateOptions& options) {
  benchmark_preset(preset);
  const fs::path dir =
      fs::path(cache_dir) / "datasets" / (preset + "-" + generation_key(preset, options));
  if (fs::is_regular_file(dir / "dataset.json")) return dir.string();
  // Each process generates into its own directory and renames it into place: shards of a cluster
  // job that all find the dataset missing each build it, and the first rename wins.
  char host[256] = "host";
  ::gethostname(host, sizeof(host) - 1);
  const fs::path tmp = dir.string() + ".partial-" + host + "-" + std::to_string(::getpid());
  std::error_code ec;
  fs::remove_all(tmp, ec);
  try {
    generate_benchmark_dataset(tmp.string(), preset, options);
  } catch (...) {
    fs::remove_all(tmp, ec);  // a failed or interrupted generation leaves nothing behind
    throw;
  }
  fs::rename(tmp, dir, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove_all(tmp, ignored);
    if (fs::is_regular_file(dir / "dataset.json")) return dir.string();  // another process won
    throw Error(dir.string() + ": cannot move the generated dataset into place (" + ec.message() +
                ")");
  }
  return dir.string();
}

}  // namespace lmk
