// SPDX-License-Identifier: BSD-3-Clause
// lmk bench [SCENE LANDMARK] [--repeats N] [--reference-seeds N] [--threads N] [--frames N]
//           [--json FILE]:
// the fast search and the paper's reference search side by side, on the same scene and landmark
// in one run: median seconds per search, their ratio, and peak memory.
//
// Without SCENE and LANDMARK it uses the real milk-carton frame from the shared data (--data, or
// $LMK_SHARED_DATA, or ../shared/data beside the source tree), and a rendered tabletop frame with
// its carton when that is absent. The reference search runs 5% of the points as seeds (at most
// 1000), each a 50-iteration PCL ICP: minutes per search. It is run on a capped number of seeds and
// its per-search time is extrapolated from the per-seed time; the output says so.

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "lmk/datasets/real_data.h"
#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/statistics.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/geometry/worker_threads.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/occupancy/tsdf_volume.h"
#include "lmk/search/find_landmark.h"
#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/tabletop_scene.h"
#include "tools/bench_motion.h"
#include "tools/cli_common.h"

namespace lmk::cli {
namespace {

namespace fs = std::filesystem;

struct BenchOptions {
  std::string scene, landmark, data, json;
  int repeats = 10;
  std::size_t reference_seeds = 20;
  int threads = 2;
  int frames = 1;  ///< > 1: also fuse this many frames of the scene, and search the fused frame
  bool motion = false;  ///< time checked arm motions instead (tools/bench_motion.h)
  MotionBenchOptions motions;
};

struct Workload {
  std::string description;
  PointCloud scene;
  Landmark landmark;
};

Workload load_workload(const BenchOptions& o) {
  Workload w;
  if (!o.scene.empty()) {
    w.description = o.landmark + " in " + o.scene;
    w.scene = read_cloud(o.scene);
    w.landmark = load_landmark(o.landmark);
    return w;
  }
  const fs::path data = shared_data_dir(o.data);
  if (fs::exists(data / "pcl/milk_cartoon_all_small_clorox.pcd")) {
    MilkWorkload milk = load_milk_workload(data);
    w.description = "milk carton in milk_cartoon_all_small_clorox.pcd (real 640x480 Kinect frame)";
    w.scene = std::move(milk.scene);
    w.landmark = std::move(milk.landmark);
    return w;
  }
  // No real data: the carton of the rendered tabletop scene, with margins above and around it.
  const SyntheticScene synthetic = make_tabletop_scene(1);
  w.description = "carton in a rendered 640x480 tabletop frame (shared data absent)";
  w.scene = render_depth(synthetic.mesh, synthetic.T_world_sensor);
  Box box = synthetic.objects.front().box;
  box.size += Eigen::Vector3d(0.04, 0.04, 0.02);
  box.pose.translation().z() += 0.011;  // keep the bottom above the table top
  w.landmark = capture(w.scene, box, "carton");
  return w;
}

// The benchmark's samples are never empty: --repeats is checked to be at least 1.
double median_of(const std::vector<double>& v) { return *median(v); }

// The process's peak resident memory so far, MiB (Linux reports ru_maxrss in KiB).
double peak_memory_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

// Fusing o.frames copies of the scene's frame (the work of as many frames: every kept voxel is
// looked up in each) and searching the fused frame, each o.repeats times, against the one-frame
// search's median `one_frame` of the same run.
nlohmann::json bench_fused(const Workload& w, const BenchOptions& o, const LandmarkIndex& prepared,
                           const FindSettings& fast, double one_frame) {
  const std::vector<DepthFrame> frames(static_cast<std::size_t>(o.frames), DepthFrame{&w.scene});
  std::vector<double> fusing, searching;
  PointCloud scene;
  for (int k = 0; k < o.repeats; ++k) {
    const Stopwatch stopwatch;
    with_worker_threads(o.threads, [&] { scene = fuse_frames(frames); });
    fusing.push_back(stopwatch.seconds());
    const SceneIndex index(scene, fast.scene);
    const FindResult r = find_landmark(index, prepared, fast);
    searching.push_back(r.stats.seconds_total + index.seconds_to_build());
  }
  const double peak = peak_memory_mib();
  std::printf("\nfused              %d frames of it, %d times\n", o.frames, o.repeats);
  std::printf("  median fusion     %.4f s (%u x %u fused frame), %.2fx the one-frame search\n",
              median_of(fusing), scene.width, scene.height, median_of(fusing) / one_frame);
  std::printf("  median search     %.4f s on the fused frame, %.2fx the one-frame search\n",
              median_of(searching), median_of(searching) / one_frame);
  std::printf("  peak memory       %.0f MiB (process, after fusing)\n", peak);
  return {{"frames", o.frames},
          {"median_seconds_fusion", median_of(fusing)},
          {"fusion_ratio_to_one_frame_search", median_of(fusing) / one_frame},
          {"median_seconds_search_fused", median_of(searching)},
          {"search_ratio_to_one_frame", median_of(searching) / one_frame},
          {"peak_memory_mib", peak}};
}

// lmk::Error naming the first option the benchmark cannot run with.
void check_bench_options(const BenchOptions& o) {
  if (o.scene.empty() != o.landmark.empty()) {
    throw Error("bench: give both SCENE and LANDMARK, or neither for the built-in workload");
  }
  if (o.repeats < 1) throw Error("bench: --repeats must be at least 1");
  if (o.reference_seeds < 1) throw Error("bench: --reference-seeds must be at least 1");
  if (o.frames < 1 || static_cast<std::size_t>(o.frames) > kMaxFusedFrames) {
    throw Error("bench: --frames must be 1 to " + std::to_string(kMaxFusedFrames));
  }
  check_worker_threads(o.threads, "bench: --threads");
}

// The fast searches' timings, each repeat's, and the work the last one did.
struct FastRuns {
  std::vector<double> total, preprocess, search, vote, coarse, fine;
  std::size_t matches = 0;
  SearchStats last;
  double peak_mib = 0.0;
  double median() const { return median_of(total); }
};

// Fast: the landmark is prepared once, as a robot or an evaluation does (LandmarkIndex); each
// repeat is then a whole search from the raw frame, the scene index built for this one landmark
// (preprocessing amortised over one landmark, the worst case).
FastRuns run_fast(const Workload& w, const BenchOptions& o, const LandmarkIndex& prepared,
                  const FindSettings& fast) {
  FastRuns runs;
  for (int k = 0; k < o.repeats; ++k) {
    const SceneIndex index(w.scene, fast.scene);
    FindResult r = find_landmark(index, prepared, fast);
    r.stats.seconds_preprocess += index.seconds_to_build();
    r.stats.seconds_total += index.seconds_to_build();
    runs.total.push_back(r.stats.seconds_total);
    runs.preprocess.push_back(r.stats.seconds_preprocess);
    runs.search.push_back(r.stats.seconds_total - r.stats.seconds_preprocess);
    runs.vote.push_back(r.stats.fast.seconds_vote);
    runs.coarse.push_back(r.stats.fast.seconds_coarse);
    runs.fine.push_back(r.stats.fast.seconds_fine);
    runs.matches = r.matches.size();
    runs.last = r.stats;
  }
  runs.peak_mib = peak_memory_mib();
  std::printf("\nfast               %d searches\n", o.repeats);
  std::printf("  median per search %.4f s (scene preprocessing %.4f s + search %.4f s)\n",
              runs.median(), median_of(runs.preprocess), median_of(runs.search));
  std::printf("  stages (median)   vote %.4f s, coarse %.4f s, fine %.4f s\n", median_of(runs.vote),
              median_of(runs.coarse), median_of(runs.fine));
  std::printf(
      "  work              %zu scene points, %zu seeds, %zu poses, %zu clusters, %zu refined\n",
      runs.last.scene_points_used, runs.last.seeds, runs.last.fast.poses, runs.last.fast.clusters,
      runs.last.fast.refined);
  std::printf("  matches           %zu\n", runs.matches);
  std::printf("  peak memory       %.0f MiB (process, after the fast searches)\n", runs.peak_mib);
  return runs;
}

// The reference search: a capped run, extrapolated to the full seed count.
struct ReferenceRun {
  std::size_t seeds_run = 0, full_seeds = 0;
  double per_seed = 0.0, per_search = 0.0, peak_mib = 0.0;
};

ReferenceRun run_reference(const Workload& w, const BenchOptions& o) {
  FindSettings reference;
  reference.method = SearchMethod::reference;
  reference.execution.threads = o.threads;
  const FindSettings full = reference.resolved();
  reference.sampling.max_seeds = o.reference_seeds;
  const FindResult r = find_landmark(w.scene, w.landmark, reference);
  ReferenceRun run;
  run.seeds_run = r.stats.seeds;
  run.full_seeds =
      std::min(*full.sampling.max_seeds,
               static_cast<std::size_t>(std::ceil(full.reference.sample_fraction *
                                                  static_cast<double>(r.stats.scene_points_used))));
  run.per_seed = r.stats.seconds_search / static_cast<double>(r.stats.seeds);
  run.per_search = r.stats.seconds_preprocess + run.per_seed * static_cast<double>(run.full_seeds);
  run.peak_mib = peak_memory_mib();
  std::printf("\nreference          %zu seeds run (capped; a full search runs %zu)\n",
              run.seeds_run, run.full_seeds);
  std::printf("  per seed          %.4f s\n", run.per_seed);
  std::printf("  per search        %.1f s (extrapolated: preprocessing + %zu seeds x per seed)\n",
              run.per_search, run.full_seeds);
  std::printf("  peak memory       %.0f MiB (process, after both)\n", run.peak_mib);
  return run;
}

// --json's record of the run.
nlohmann::json bench_json(const Workload& w, const BenchOptions& o, const LandmarkIndex& prepared,
                          const FastRuns& fast, const ReferenceRun& reference, double ratio,
                          const nlohmann::json& fused) {
  return {{"workload", w.description},
          {"threads", o.threads},
          {"fast",
           {{"searches", o.repeats},
            {"seconds_landmark_index", prepared.seconds_to_build()},
            {"median_seconds_vote", median_of(fast.vote)},
            {"median_seconds_coarse", median_of(fast.coarse)},
            {"median_seconds_fine", median_of(fast.fine)},
            {"median_seconds_per_search", fast.median()},
            {"median_seconds_preprocess", median_of(fast.preprocess)},
            {"median_seconds_search", median_of(fast.search)},
            {"matches", fast.matches},
            {"peak_memory_mib", fast.peak_mib}}},
          {"reference",
           {{"seeds_run", reference.seeds_run},
            {"seeds_full_search", reference.full_seeds},
            {"seconds_per_seed", reference.per_seed},
            {"seconds_per_search_extrapolated", reference.per_search},
            {"peak_memory_mib", reference.peak_mib}}},
          {"ratio", ratio},
          {"fused", fused}};
}

int run_bench(const BenchOptions& o) {
  if (o.motion) {
    if (!o.scene.empty() || o.frames != 1)
      throw Error("bench --motion: SCENE, LANDMARK and --frames do not apply");
    MotionBenchOptions motions = o.motions;
    motions.json = o.json;
    return run_motion_bench(motions);
  }
  check_bench_options(o);
  const Workload w = load_workload(o);
  std::printf("workload           %s\n", w.description.c_str());
  std::printf("landmark           '%s', %zu points\n", w.landmark.name.c_str(),
              w.landmark.points.size());
  std::printf("threads            %s\n",
              o.threads > 0 ? std::to_string(o.threads).c_str() : "all cores");

  FindSettings fast;
  fast.execution.threads = o.threads;
  const LandmarkIndex prepared(w.landmark, fast);
  std::printf("landmark index     %.4f s (once per landmark)\n", prepared.seconds_to_build());
  const FastRuns fast_runs = run_fast(w, o, prepared, fast);
  nlohmann::json fused = nullptr;
  if (o.frames > 1) fused = bench_fused(w, o, prepared, fast, fast_runs.median());
  const ReferenceRun reference = run_reference(w, o);
  const double ratio = reference.per_search / fast_runs.median();
  std::printf("\nspeed-up           %.0fx (reference per search / fast per search)\n", ratio);
  if (!o.json.empty()) {
    write_text_atomically(
        o.json, bench_json(w, o, prepared, fast_runs, reference, ratio, fused).dump(2) + "\n");
  }
  return kOk;
}

}  // namespace

Subcommand add_bench(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* sub =
      app.add_subcommand("bench", "Time the fast search against the paper's reference search");
  sub->add_option("scene", o->scene, "Scene cloud (default: the built-in milk-carton workload)");
  sub->add_option("landmark", o->landmark, "Landmark file (.lmk), with SCENE");
  sub->add_option("--data", o->data, "Shared data directory (default $LMK_SHARED_DATA)");
  sub->add_option("--repeats", o->repeats, "Fast searches to time")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--reference-seeds", o->reference_seeds,
                  "Seeds the reference search runs before extrapolating")
      ->check(non_negative_whole())
      ->capture_default_str();
  sub->add_option("--frames", o->frames,
                  "Also fuse this many frames of the scene (its frame repeated: the work of as "
                  "many frames) and search the fused frame, against the one-frame search")
      ->capture_default_str();
  sub->add_option("--threads", o->threads, "Worker threads; 0 uses every core")
      ->check(worker_threads())
      ->capture_default_str();
  sub->add_option("--json", o->json, "Also write the figures as JSON to FILE");
  CLI::Option* motion = sub->add_flag(
      "--motion", o->motion,
      "Instead, time checking the PR2 right arm's straight joint lines and planning around a box "
      "where they touch it (issue #60)");
  sub->add_option("--scenes", o->motions.scenes, "With --motion: random scenes to time")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str()
      ->needs(motion);
  sub->add_option("--planning-time", o->motions.check.planning_time,
                  "With --motion: seconds a plan around the box may take")
      ->check(CLI::Range(0.01, 60.0))
      ->capture_default_str()
      ->needs(motion);
  sub->add_option("--planning-checks", o->motions.check.planning_checks,
                  "With --motion: configurations a plan around the box may check")
      ->check(CLI::Range(std::size_t{1}, std::size_t{100000000}))
      ->capture_default_str()
      ->needs(motion);
  return {sub, [o] { return run_bench(*o); }};
}

}  // namespace lmk::cli
