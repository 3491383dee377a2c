// The paper-faithful reference search, timed: seconds per seed and per search.
//
//   build/bench/bench_reference [--seeds N] [--threads T]
//
// By default it captures the milk carton in ../shared/data/pcl/milk_cartoon_all_small_clorox.pcd
// (or $LMK_SHARED_DATA) and searches that scene; without the data it uses a rendered tabletop frame
// and its carton. A full search runs 5% of the points as seeds, at most 1000, each a 50-iteration
// PCL ICP: minutes. So the run is capped at N seeds and the per-search time is extrapolated from
// the per-seed time, and the output says so.

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "eval/depth_sensor.h"
#include "eval/real_data.h"
#include "eval/tabletop_scene.h"
#include "geometry/cloud_io.h"
#include "geometry/pose.h"
#include "geometry/voxel_grid.h"
#include "landmark/find_landmark.h"

namespace {

namespace fs = std::filesystem;

struct Workload {
  std::string description;
  lmk::PointCloud scene;
  lmk::Landmark landmark;
};

Workload load_workload() {
  const char* env = std::getenv("LMK_SHARED_DATA");
  const fs::path data = env && *env ? fs::path(env) : fs::path(LMK_SHARED_DATA_DIR);
  const fs::path milk_scene = data / "pcl/milk_cartoon_all_small_clorox.pcd";
  Workload w;
  if (fs::exists(milk_scene)) {
    w.description = "milk carton in " + milk_scene.filename().string() + " (real Kinect frame)";
    w.scene = lmk::read_cloud(milk_scene.string());
    w.landmark = lmk::capture(
        w.scene, lmk::milk_carton_box(lmk::read_cloud((data / "pcl/milk.pcd").string())), "milk");
    return w;
  }
  // No real data: the carton of the rendered tabletop scene, with margins above and around it.
  const lmk::SyntheticScene synthetic = lmk::make_tabletop_scene(1);
  w.description = "carton in a rendered 640x480 tabletop frame (../shared/data absent)";
  w.scene = lmk::render_depth(synthetic.mesh, synthetic.T_world_sensor);
  lmk::Box box = synthetic.objects.front().box;
  box.size += Eigen::Vector3d(0.04, 0.04, 0.02);
  box.pose.translation().z() += 0.011;  // keep the bottom above the table top
  w.landmark = lmk::capture(w.scene, box, "carton");
  return w;
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t seeds = 40;
  int threads = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--seeds" && i + 1 < argc) {
      seeds = std::stoul(argv[++i]);
    } else if (arg == "--threads" && i + 1 < argc) {
      threads = std::stoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: bench_reference [--seeds N] [--threads T]\n");
      return 2;
    }
  }
  try {
    const Workload w = load_workload();
    lmk::FindSettings settings;
    settings.threads = threads;
    const std::size_t full_seeds = std::min<std::size_t>(
        settings.max_seeds,
        static_cast<std::size_t>(std::ceil(
            settings.sample_fraction * lmk::voxel_downsample(w.scene, settings.leaf_size).size())));
    settings.max_seeds = seeds;
    const lmk::FindResult r = lmk::find_landmark(w.scene, w.landmark, settings);
    const double per_seed = r.stats.seconds_search / static_cast<double>(r.stats.seeds);
    std::printf("workload          %s\n", w.description.c_str());
    std::printf("scene             %zu finite points, %zu after 5 mm voxels\n",
                r.stats.scene_points, r.stats.scene_points_used);
    std::printf("landmark          %zu points\n", w.landmark.points.size());
    std::printf("threads           %s\n",
                threads > 0 ? std::to_string(threads).c_str() : "all cores");
    std::printf("seeds run         %zu (capped; a full search runs %zu)\n", r.stats.seeds,
                full_seeds);
    std::printf("ICP iterations    %.1f per seed\n",
                static_cast<double>(r.stats.icp_iterations) / static_cast<double>(r.stats.seeds));
    std::printf("preprocess        %.3f s\n", r.stats.seconds_preprocess);
    std::printf("seconds per seed  %.4f (wall clock, ICP and scoring)\n", per_seed);
    std::printf("seconds per search %.1f (extrapolated: preprocess + %zu seeds x per-seed)\n",
                r.stats.seconds_preprocess + per_seed * static_cast<double>(full_seeds),
                full_seeds);
    std::printf("matches           %zu (from the capped run)\n", r.matches.size());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_reference: %s\n", e.what());
    return 1;
  }
  return 0;
}
