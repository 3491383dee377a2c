// SPDX-License-Identifier: BSD-3-Clause
// lmk find SCENE [SCENE...] LANDMARK [--poses F] [search settings: --method M --metric NAME
//          --threshold T ...] [--threads N] [--json FILE|-]: every instance of a landmark, with its
//          pose and error. Several frames of one scene are fused into one (tsdf_volume.h) first.

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/pose_list.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/geometry/worker_threads.h"
#include "lmk/landmark/depth_correction_file.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/occupancy/tsdf_volume.h"
#include "lmk/search/find_landmark.h"
#include "lmk/search/internal/find_result_json.h"
#include "lmk/search/scene_footprint.h"
#include "tools/bag_input.h"
#include "tools/cli_common.h"
#include "tools/progress.h"

namespace lmk::cli {
namespace {

struct FindOptions {
  BagOptions bag;
  std::vector<std::string> inputs;  ///< the scene's frames, then the landmark
  std::vector<std::string> scenes;
  std::string landmark, json, depth_correction, poses;
  bool timings = false;
  bool rejected = false;
  FindSettings settings;
};

// "0.93", or "-" where no calibration was fitted for the metric.
std::string format_confidence(double probability) {
  if (std::isnan(probability)) return "-";
  char text[16];
  std::snprintf(text, sizeof(text), "%.2f", probability);
  return text;
}

void print_table(const FindResult& r, const std::string& name) {
  const SearchStats& s = r.stats;
  const std::string rejected = describe_rejections(s);
  const std::string why = rejected.empty() ? "" : "; " + rejected;
  std::printf(
      "%zu match%s for '%s' (%s, metric %s, threshold %s, %zu seeds, %zu scene points,"
      " %.2f s%s)\n",
      r.matches.size(), r.matches.size() == 1 ? "" : "es", name.c_str(),
      setting_name(s.method).c_str(), s.metric.c_str(), format_error(s.threshold, s.metric).c_str(),
      s.seeds, s.scene_points_used, s.seconds_total, why.c_str());
  if (r.matches.empty()) return;
  // The metrics that measure support and test empty space show those; the paper's, its counts.
  const bool grid_terms = r.matches.front().terms.support.has_value();
  const ErrorDisplay& shown = find_error_metric(s.metric).display;
  std::printf("%4s %9s %9s %9s %8s %8s %8s %9s %10s", "rank", "x", "y", "z", "roll", "pitch", "yaw",
              ("error_" + shown.column).c_str(), "confidence");
  if (grid_terms) {
    std::printf(" %8s %11s\n", "coverage", "empty_viol");
  } else {
    std::printf(" %7s %7s %6s\n", "s->l", "l->s", "inbox");
  }
  for (std::size_t i = 0; i < r.matches.size(); ++i) {
    const Match& m = r.matches[i];
    const Eigen::Vector3d c = m.box.center();
    const Eigen::Vector3d rpy = rpy_degrees(m.box.pose.linear());
    std::printf("%4zu %9.4f %9.4f %9.4f %8.2f %8.2f %8.2f %9.3f %10s", i + 1, c.x(), c.y(), c.z(),
                rpy.x(), rpy.y(), rpy.z(), shown.scale * m.error,
                format_confidence(m.confidence.probability).c_str());
    if (grid_terms) {
      const EmptySpaceTerms empty = m.terms.empty_space.value_or(EmptySpaceTerms{});
      const std::string viol =
          std::to_string(empty.violations) + "/" + std::to_string(empty.probes);
      std::printf(" %8.3f %11s\n", m.terms.coverage(), viol.c_str());
    } else {
      std::printf(" %7zu %7zu %6zu\n", m.terms.scene_to_landmark_count,
                  m.terms.landmark_to_scene_count, m.terms.scene_points_in_box);
    }
    if (!m.confidence.doubt.empty()) std::printf("     doubt: %s\n", m.confidence.doubt.c_str());
  }
}

/// The frames of one input: a cloud file's one frame, or a bag's (several with --frames or
/// --time-window), depth-corrected.
std::vector<PointCloud> read_frames(FindOptions& o, const std::string& path) {
  bool in_base_frame = false;
  std::vector<PointCloud> frames;
  if (is_bag(path)) {
    frames = read_bag_scenes(path, o.bag, in_base_frame);
  } else {
    frames.push_back(read_cloud(path));
  }
  for (PointCloud& frame : frames) correct_depth(frame, o.depth_correction);
  // A scene in the robot's base frame has +z up, as --base-frame says, unless --up says otherwise.
  if (in_base_frame && !o.settings.scene.up) o.settings.scene.base_frame = true;
  return frames;
}

// The scene: one frame as it is, several fused into one (with --poses, each moved into the common
// frame first; without, they are in it already: a static head's frames, or clouds in a robot's base
// frame, as a bag's are).
PointCloud read_scene(FindOptions& o) {
  const bool bag = o.scenes.size() == 1 && is_bag(o.scenes.front());
  if (bag && !o.poses.empty()) {
    throw Error("--poses: a bag's frames are placed by its own TF; give no --poses with a bag");
  }
  if (!bag && o.bag.several()) {
    throw Error(
        "--frames and --time-window choose frames of one bag; give several cloud files "
        "to fuse them instead");
  }
  // Counted and priced before any frame is read (issue #61, finding 3): 500 files took 2.5 GB
  // before the count was checked, and 30 frames of 4096 x 4096 points 7.3 GB.
  if (o.scenes.size() > kMaxFusedFrames) {
    throw Error(std::to_string(o.scenes.size()) + " frames: lmk fuses at most " +
                std::to_string(kMaxFusedFrames) + " frames of one scene");
  }
  std::size_t reading = 0;
  for (const std::string& path : o.scenes) {
    if (!is_bag(path)) reading += cloud_read_price(path);
  }
  const std::size_t available = available_memory();
  if (reading > available) {
    throw Error("reading these " + std::to_string(o.scenes.size()) + " frames would take about " +
                describe_bytes(reading) + ", more than the " + describe_bytes(available) +
                " this machine has available");
  }
  std::vector<PointCloud> frames;
  for (const std::string& path : o.scenes) {
    if (is_bag(path) && o.scenes.size() > 1) {
      throw Error(path +
                  ": a bag cannot be fused with other files; use --frames N to fuse its own");
    }
    for (PointCloud& frame : read_frames(o, path)) frames.push_back(std::move(frame));
  }
  if (frames.size() == 1 && o.poses.empty()) return std::move(frames.front());
  std::vector<Eigen::Isometry3d> poses(frames.size(), Eigen::Isometry3d::Identity());
  if (!o.poses.empty()) {
    poses = read_pose_list(o.poses);
    if (poses.size() != frames.size()) {
      throw Error(o.poses + ": " + std::to_string(poses.size()) + " poses for " +
                  std::to_string(frames.size()) + " frames (one line per frame, in order)");
    }
  }
  std::vector<DepthFrame> fused;
  for (std::size_t i = 0; i < frames.size(); ++i) fused.push_back({&frames[i], poses[i]});
  const Stopwatch stopwatch;
  PointCloud scene;
  // The volume, priced like a search, must fit beside the frames.
  FusionSettings fusion;
  fusion.max_bytes = available > reading ? available - reading : 0;
  with_worker_threads(o.settings.execution.threads, [&] { scene = fuse_frames(fused, fusion); });
  if (o.json != "-") {
    std::printf("%zu frames fused into one %u x %u frame, seen from the first's sensor (%.2f s)\n",
                frames.size(), scene.width, scene.height, stopwatch.seconds());
  }
  return scene;
}

int run_find(FindOptions& o) {
  o.landmark = o.inputs.back();
  o.scenes.assign(o.inputs.begin(), o.inputs.end() - 1);
  for (const std::string& scene : o.scenes) {
    if (!is_bag(scene)) format_from_path(scene);
  }
  const Landmark landmark = load_landmark(o.landmark);
  const PointCloud scene = read_scene(o);
  // A scene whose index would not fit this machine is refused before anything is built.
  require_footprint_fits(scene, o.settings.scene);
  ProgressBar bar("find " + landmark.name);
  o.settings.execution.progress = [&bar](std::size_t done, std::size_t total) {
    bar.update(done, total);
  };
  const FindResult result = find_landmark(scene, landmark, o.settings);
  o.settings.execution.progress = nullptr;
  const auto json_text = [&] {
    return json_output(detail::find_result_to_json(result, o.rejected), o.timings).dump(2) + "\n";
  };
  if (o.json == "-") {
    std::cout << json_text();
    return kOk;
  }
  print_table(result, landmark.name);
  if (!o.json.empty()) write_text_atomically(o.json, json_text());
  return kOk;
}

}  // namespace

Subcommand add_find(CLI::App& app) {
  auto o = std::make_shared<FindOptions>();
  FindSettings& s = o->settings;
  CLI::App* sub = app.add_subcommand("find", "Find every instance of a landmark in a scene");
  sub->add_option(
         "inputs", o->inputs,
         "SCENE [SCENE...] LANDMARK: the scene cloud (.pcd, .ply, .xyz) or ROS bag (.bag), "
         "then the landmark file (.lmk). Several organised frames of one scene are fused "
         "into one before the search (docs/cli.md, \"Several frames\")")
      ->required()
      ->expected(2, -1);
  sub->add_option("--poses", o->poses,
                  "With several frames: a text file of each frame's pose in a common frame, one "
                  "line per frame, x y z qx qy qz qw (TUM's order; a timestamp may lead). Without "
                  "it the frames are in one frame already");
  add_search_options(sub, s, true);
  add_bag_options(sub, o->bag, true);
  add_depth_correction_option(sub, o->depth_correction);
  sub->add_option("--json", o->json,
                  "Write the matches and statistics as JSON to FILE, or - for stdout");
  sub->add_flag("--rejected", o->rejected,
                "With --json: also the candidates turned down after non-max suppression, each with "
                "the test it failed");
  add_timings_flag(sub, o->timings);
  return {sub, [o] { return run_find(*o); }};
}

}  // namespace lmk::cli
