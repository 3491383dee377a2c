// SPDX-License-Identifier: BSD-3-Clause
// lmk gen: render synthetic data with the simulated Kinect.
//   lmk gen OUT.pcd [--seed S] [--no-noise]            one tabletop frame (the demo scene)
//   lmk gen --preset NAME OUT_DIR [--seeds N] [--hard]  a benchmark dataset (docs/datasets.md)
//   lmk gen --preset moving OUT_DIR [--frames N]        frame sequences of pushed landmarks
//   lmk gen OUT_DIR --from-rgbd SEQ                      real cross-view pairs of an RGB-D sequence

#include <cstdio>
#include <memory>

#include "lmk/datasets/benchmark_dataset.h"
#include "lmk/datasets/mosd_dataset.h"
#include "lmk/datasets/moving_dataset.h"
#include "lmk/datasets/rgbd_dataset.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/landmark/depth_correction_file.h"
#include "lmk/occupancy/tsdf_volume.h"
#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/tabletop_scene.h"
#include "tools/bag_input.h"
#include "tools/cli_common.h"
#include "tools/progress.h"

namespace lmk::cli {
namespace {

struct GenOptions {
  std::string output;
  std::uint64_t seed = 0;
  bool no_noise = false;
  std::string preset;
  std::optional<int> seeds;
  bool hard = false;
  std::string types;  ///< comma-separated
  std::string shard;  ///< K/N
  bool merge = false;
  std::string from_mosd;
  int copies = 2, frames = 0;  ///< --from-mosd: the first N frames; --preset: frames fused
  double head_turn = 0.0;      ///< --preset --frames: degrees the head pans between frames
  std::string from_bag;
  BagOptions bag;
  std::vector<std::string> landmarks;
  std::optional<std::size_t> stride;  ///< default: 1 for a bag, 5 for an RGB-D sequence
  std::size_t views = 1;              ///< --from-rgbd: each box also from 2 up to this many views
  std::optional<std::size_t> view_gap;
  std::size_t fuse = 1;  ///< --from-rgbd: each scene fused from this many consecutive frames
  std::string from_rgbd;
  std::vector<double> intrinsics;  ///< fx fy cx cy
  bool registered_colour = false;
  bool keep_warned = false;
  std::optional<double> box_side;
  int depth_smoothing = kDefaultDepthSmoothing;
  bool calibrate_depth = false;
  std::string depth_correction;  ///< a file of lmk calibrate-depth
  std::vector<std::size_t> gap;  ///< min max, frames
};

int run_tabletop(const GenOptions& options) {
  format_from_path(options.output);  // reject an unknown extension before rendering
  const SyntheticScene scene = make_tabletop_scene(options.seed);
  DepthSensorSettings sensor;
  sensor.seed = options.seed;
  sensor.noise = !options.no_noise;
  const PointCloud cloud = render_depth(scene.mesh, scene.T_world_sensor, sensor);
  write_cloud(options.output, cloud);
  std::printf("wrote %s: %ux%u frame, %zu returns, world frame (z up)\n", options.output.c_str(),
              cloud.width, cloud.height, cloud.count_finite());
  for (const SceneObject& object : scene.objects) {
    const Eigen::Vector3d c = object.box.center();
    const Eigen::Vector3d rpy = rpy_degrees(object.box.pose.linear());
    std::printf("  %-8s centre %7.3f %7.3f %7.3f  yaw %6.1f deg\n", object.name.c_str(), c.x(),
                c.y(), c.z(), rpy.z());
  }
  return kOk;
}

int run_preset(const GenOptions& options) {
  benchmark_preset(options.preset);  // an unknown name fails before anything is written
  GenerateOptions generate;
  generate.seeds = options.seeds;
  generate.views = static_cast<int>(options.views);
  generate.hard = options.hard;
  generate.noise = !options.no_noise;
  generate.types = split_commas(options.types);
  if (options.seed != 0) generate.first_seed = options.seed;
  if (!options.shard.empty()) generate.shard = parse_shard(options.shard);
  generate.merge = options.merge;
  generate.frames = std::max(1, options.frames);
  generate.head_turn = options.head_turn;
  const std::string label =
      "gen " + options.preset + (options.shard.empty() ? "" : " " + options.shard);
  ProgressBar bar(label);
  generate.progress = [&bar](std::size_t done, std::size_t total) { bar.update(done, total); };
  const Stopwatch stopwatch;
  const Generated generated = generate_benchmark(options.output, options.preset, generate);
  const Dataset& dataset = generated.dataset;
  const double seconds = stopwatch.seconds();
  if (generate.shard) {
    std::printf(
        "%s: %zu of the dataset's scenes are this shard's: %zu rendered, %zu already there "
        "(%.1f s); once every shard has run, the same command with --merge in place of --shard "
        "writes %s/dataset.json\n",
        label.c_str(), dataset.scenes.size(), generated.rendered, generated.kept, seconds,
        options.output.c_str());
    return kOk;
  }
  std::size_t instances = 0, in_context = 0;
  for (const DatasetScene& scene : dataset.scenes) {
    for (const DatasetPair& pair : scene.pairs) {
      instances += pair.instances.size();
      in_context += pair.in_context ? 1 : 0;
    }
  }
  std::printf(
      "wrote dataset '%s' to %s: %zu landmarks, %zu scenes, %zu in-context pairs, %zu "
      "ground-truth instances (%.1f s)\n",
      dataset.name.c_str(), options.output.c_str(), dataset.landmarks.size(), dataset.scenes.size(),
      in_context, instances, seconds);
  return kOk;
}

// The moving preset: sequences for lmk track and lmk eval-track, not scenes of the paper's types.
int run_moving(const GenOptions& options) {
  if (options.hard || !options.shard.empty() || options.merge || options.views > 1 ||
      options.head_turn != 0.0)
    throw Error("gen --preset moving takes --seeds, --seed, --frames, --types and --no-noise only");
  MovingOptions moving;
  if (options.seeds) moving.seeds = *options.seeds;
  if (options.frames > 0) moving.frames = options.frames;
  if (options.seed != 0) moving.first_seed = options.seed;
  moving.noise = !options.no_noise;
  moving.landmarks = split_commas(options.types);
  ProgressBar bar("gen moving");
  moving.progress = [&bar](std::size_t done, std::size_t total) { bar.update(done, total); };
  const Stopwatch stopwatch;
  const Dataset dataset = generate_moving_dataset(options.output, moving);
  std::printf(
      "wrote dataset 'moving' to %s: %zu landmarks, %d sequences of %d frames each (%.1f s); "
      "follow them with: lmk eval-track %s\n",
      options.output.c_str(), dataset.landmarks.size(),
      static_cast<int>(dataset.landmarks.size()) * moving.seeds, moving.frames, stopwatch.seconds(),
      options.output.c_str());
  return kOk;
}

int run_mosd(const GenOptions& options) {
  MosdOptions mosd;
  mosd.copies = options.copies;
  mosd.max_frames = options.frames;
  ProgressBar bar("gen mosd");
  mosd.progress = [&bar](std::size_t done, std::size_t total) { bar.update(done, total); };
  const Dataset dataset = generate_mosd_dataset(options.from_mosd, options.output, mosd);
  std::printf(
      "wrote dataset '%s' to %s: %zu landmarks, %zu scenes (rigidly moved copies of labelled "
      "frames); evaluate it with --pairs in-context\n",
      dataset.name.c_str(), options.output.c_str(), dataset.landmarks.size(),
      dataset.scenes.size());
  return kOk;
}

int run_rgbd(const GenOptions& options) {
  RgbdDatasetOptions rgbd;
  if (!options.intrinsics.empty()) rgbd.read.intrinsics = intrinsics_of_option(options.intrinsics);
  if (options.registered_colour) rgbd.read.colour_registered = true;
  rgbd.keep_warned = options.keep_warned;
  rgbd.box_side = options.box_side;
  rgbd.depth_smoothing = options.depth_smoothing;
  rgbd.calibrate_depth = options.calibrate_depth;
  if (!options.depth_correction.empty())
    rgbd.depth_correction = load_depth_correction(options.depth_correction);
  if (options.stride) rgbd.frame_stride = *options.stride;
  if (!options.gap.empty()) {
    rgbd.min_gap = options.gap[0];
    rgbd.max_gap = options.gap[1];
  }
  rgbd.views = options.views;
  if (options.view_gap) rgbd.view_gap = *options.view_gap;
  rgbd.fuse = options.fuse;
  ProgressBar bar("gen rgbd");
  rgbd.progress = [&bar](std::size_t done, std::size_t total) { bar.update(done, total); };
  const Stopwatch stopwatch;
  const RgbdImport import = generate_rgbd_dataset(options.from_rgbd, options.output, rgbd);
  const double seconds = stopwatch.seconds();
  if (const auto& c = import.depth_calibration) {
    std::printf(
        "depth corrected with a fit %s: %d x %d cells, %zu correspondences, their disagreement "
        "%.1f mm -> %.1f mm RMS\n",
        options.calibrate_depth ? "on the frames left out of the dataset"
                                : ("from " + options.depth_correction).c_str(),
        c->correction.cols, c->correction.rows, c->correspondences, 1000.0 * c->rms_before,
        1000.0 * c->rms_after);
  }
  std::size_t refused = 0;
  std::string reasons;
  for (const auto& [why, n] : import.refused) {
    refused += n;
    reasons += (reasons.empty() ? "" : ", ") + std::to_string(n) + " " + why;
  }
  std::printf(
      "wrote dataset '%s' to %s (%s layout): %zu boxes of %.0f cm drawn, %zu refused%s%s%s, %zu "
      "landmarks; %zu scenes, %zu pairs, %zu left out as their poses disagree with the frames' "
      "registration (import.json; %.1f s); evaluate it with --pairs in-context\n",
      import.dataset.name.c_str(), options.output.c_str(), import.layout.c_str(), import.boxes,
      100.0 * import.box_side, refused, reasons.empty() ? "" : " (", reasons.c_str(),
      reasons.empty() ? "" : ")", import.dataset.landmarks.size(), import.dataset.scenes.size(),
      import.pairs, import.pairs_left_out, seconds);
  return kOk;
}

// The subcommand with its output and the synthetic presets' options.
CLI::App* add_gen_subcommand(CLI::App& app, GenOptions& o) {
  std::string presets;
  for (const BenchmarkPreset& p : benchmark_presets())
    presets += "\n  " + p.name + ": " + p.description;
  CLI::App* sub = app.add_subcommand(
      "gen",
      "Render synthetic data with a simulated Kinect v1: one tabletop frame (carton, cup, ball), "
      "or with --preset a benchmark dataset of the paper's scene types");
  sub->add_option("output", o.output,
                  "Cloud file to write (.pcd, .ply, .xyz), or with --preset the dataset directory")
      ->required();
  presets +=
      "\n  moving: frame sequences at 30 Hz of an object pushed 0.5-3 cm a frame and once carried "
      "20-40 cm away, the camera still or panning (lmk eval-track)";
  sub->add_option("--preset", o.preset, "Write a benchmark dataset:" + presets);
  sub->add_option("--seed", o.seed,
                  "Scene and noise seed; with --preset the first scene seed (default 1: seed 0 is "
                  "where the landmarks are captured)")
      ->check(non_negative_whole());
  sub->add_option("--seeds", o.seeds,
                  "With --preset: scenes per scene type (1 to 1000; the paper's are 5 to 10)")
      ->check(CLI::Range(1, kMaxSeedsPerType));
  sub->add_flag("--hard", o.hard,
                "With --preset: strong rotations and tilts (any yaw, turned chairs, tilted walls)");
  sub->add_option("--types", o.types,
                  "With --preset: only these scene types (comma-separated, e.g. "
                  "simple/three_balls) and the landmarks in context in them; with --preset "
                  "moving, only these objects (bowl, cup, tide_bottle, spray_bottle)");
  sub->add_option(
      "--shard", o.shard,
      "With --preset: render only shard K of N (K/N), a stable share of the scenes, for "
      "one machine of a cluster; a rerun renders only what is missing (docs/cluster.md)");
  sub->add_flag("--merge", o.merge,
                "With --preset: render nothing, write dataset.json once every shard has run, or "
                "name the scenes still missing")
      ->excludes("--shard");
  return sub;
}

// The options of datasets from recorded data: mOSD's frames and ROS bags.
void add_recorded_options(CLI::App* sub, GenOptions& o) {
  sub->add_option("--from-mosd", o.from_mosd,
                  "Write a real-data dataset from the labelled mOSD learn frames in DIR "
                  "(../shared/data/mosd/learn): landmarks around the labelled objects, searched in "
                  "rigidly moved copies of their frames")
      ->check(CLI::ExistingDirectory);
  sub->add_option("--copies", o.copies, "With --from-mosd: moved copies per frame (1 to 100)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  sub->add_option("--frames", o.frames,
                  "With --from-mosd: the first N frames only (0: all). With --preset: each scene "
                  "fused from N renders with their own noise (lmk find with several frames). "
                  "With --preset moving: frames per sequence (10 to 3000, default 60)")
      ->check(CLI::Range(0, 100000));
  sub->add_flag("--no-noise", o.no_noise, "Exact depth: no sensor noise or quantisation");
  sub->add_option("--from-bag", o.from_bag,
                  "Write a dataset of a recorded session's frames (ROS bag): scenes in base_link "
                  "when its TF has it, the --landmark files, no labelled instance yet")
      ->check(CLI::ExistingFile);
  sub->add_option("--landmark", o.landmarks, "With --from-bag: a landmark file (.lmk)")
      ->check(CLI::ExistingFile);
  sub->add_option("--stride", o.stride,
                  "With --from-bag: every N-th frame (default 1); with --from-rgbd: landmarks and "
                  "scenes from every N-th frame (default 5)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{100000}));
  add_bag_options(sub, o.bag, false);
}

// The options of datasets from RGB-D sequences with camera poses, and of several views and frames.
void add_rgbd_options(CLI::App* sub, GenOptions& o) {
  sub->add_option("--from-rgbd", o.from_rgbd,
                  "Write a real-data dataset from an RGB-D sequence with camera poses in DIR "
                  "(frame-N.depth.png + .pose.txt as in ../shared/data/real, 7-Scenes and 3DMatch; "
                  "TUM RGB-D; BOP): landmarks cut with user-like boxes in every --stride-th frame "
                  "(default 5), searched in the frames --gap frames away")
      ->check(CLI::ExistingDirectory);
  sub->add_option("--intrinsics", o.intrinsics,
                  "With --from-rgbd: the depth camera's FX FY CX CY, pixels (default: the "
                  "sequence's intrinsics file)")
      ->expected(4);
  sub->add_flag("--registered-colour,--registered-color", o.registered_colour,
                "With --from-rgbd: the frames layout's colour images are registered to depth "
                "(3DMatch's SUN3D frames; 7-Scenes' are not)");
  sub->add_flag("--keep-warned", o.keep_warned,
                "With --from-rgbd: keep the landmarks the capture check warns match elsewhere in "
                "their own frame (their findings say so), as a user who ignores the warning would; "
                "default: refuse them");
  sub->add_option("--box-side", o.box_side,
                  "With --from-rgbd: side of the landmark boxes, m (default: 0.15 x the median "
                  "depth, within 0.08-0.4)")
      ->check(within(0.0, 3.0, true));  // CaptureSettings::max_box_side
  sub->add_option("--depth-smoothing", o.depth_smoothing,
                  "With --from-rgbd: capture and check the landmarks with this depth smoothing, "
                  "pixels (search them with the same --depth-smoothing)")
      ->check(CLI::Range(0, kMaxDepthSmoothingRadius))
      ->capture_default_str();
  sub->add_flag("--calibrate-depth", o.calibrate_depth,
                "With --from-rgbd: fit the camera's depth error on the frames the dataset does not "
                "use, given their poses, and correct the frames it uses (import.json records the "
                "fit)");
  sub->add_option("--depth-correction", o.depth_correction,
                  "With --from-rgbd: correct the frames it uses with this depth-correction file "
                  "(lmk calibrate-depth) instead of fitting one")
      ->check(CLI::ExistingFile)
      ->excludes("--calibrate-depth");
  sub->add_option(
         "--views", o.views,
         "Each landmark also captured from 2 up to this many views, named NAME-vK and searched "
         "where NAME is. --preset: its demonstration camera turned by +45, -45, +90 degrees "
         "about the instance; --from-rgbd: its frame and the frames --view-gap, -view-gap, ... "
         "away, registered from the poses, searched --gap frames from the nearest view")
      ->check(CLI::Range(1, 4))
      ->capture_default_str();
  sub->add_option("--view-gap", o.view_gap,
                  "With --from-rgbd --views: frames between a box's views (default 10)");
  sub->add_option("--head-turn", o.head_turn,
                  "With --preset --frames: the k-th render's camera panned by DEG x 0, +1, -1, +2, "
                  "-2, ... about the vertical through it, as a robot's head turns between looks "
                  "(default 0)")
      ->check(within(0.0, 45.0));
  sub->add_option("--fuse", o.fuse,
                  "With --from-rgbd: each scene fused from N consecutive frames about its own, "
                  "moved by the sequence's poses (lmk find with several frames; default 1: the "
                  "frame alone)")
      ->check(CLI::Range(std::size_t{1}, kMaxFusedFrames))
      ->capture_default_str();
  sub->add_option("--gap", o.gap,
                  "With --from-rgbd: MIN MAX frames between a landmark's frame and its scenes "
                  "(default 10 40)")
      ->expected(2);
}

// The dataset or frame the options ask for; lmk::Error for options that exclude each other.
int run_gen(const GenOptions& o) {
  if (!o.from_rgbd.empty()) {
    if (!o.preset.empty() || !o.from_mosd.empty() || !o.from_bag.empty())
      throw Error("--from-rgbd excludes --preset, --from-mosd and --from-bag");
    return run_rgbd(o);
  }
  if (!o.from_bag.empty()) {
    if (!o.preset.empty() || !o.from_mosd.empty())
      throw Error("--from-bag excludes --preset and --from-mosd");
    return write_bag_dataset(o.from_bag, o.bag, o.stride.value_or(1), o.landmarks, o.output);
  }
  if (!o.from_mosd.empty()) {
    if (!o.preset.empty()) throw Error("--from-mosd and --preset exclude each other");
    return run_mosd(o);
  }
  if (o.preset.empty()) {
    if (o.seeds || o.hard || !o.types.empty() || !o.shard.empty() || o.merge)
      throw Error("--seeds, --hard, --types, --shard and --merge need --preset");
    return run_tabletop(o);
  }
  if (o.preset == "moving") return run_moving(o);
  return run_preset(o);
}

}  // namespace

Subcommand add_gen(CLI::App& app) {
  auto options = std::make_shared<GenOptions>();
  CLI::App* sub = add_gen_subcommand(app, *options);
  add_recorded_options(sub, *options);
  add_rgbd_options(sub, *options);
  return {sub, [options] { return run_gen(*options); }};
}

}  // namespace lmk::cli
