// SPDX-License-Identifier: BSD-3-Clause
// The scene index's parts (search/scene_index.h), each timed alone on one frame, on one thread and
// on two: where a search's preprocessing goes (issue #63). The whole index, its frame's preparation
// included, is timed too, so that the parts can be read against it in the same run.
//
//   build/bench/bench_scene_index                      # a rendered tabletop frame
//   LMK_BENCH_FRAME=F.pcd build/bench/bench_scene_index  # your frame (issue #63: the milk frame)
//   build/bench/bench_scene_index --benchmark_filter=DistanceField --benchmark_repetitions=5

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cstdlib>
#include <optional>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/filters.h"
#include "lmk/geometry/frame_preparation.h"
#include "lmk/geometry/range_image.h"
#include "lmk/geometry/voxel_normals.h"
#include "lmk/occupancy/distance_field.h"
#include "lmk/occupancy/occupancy_grid.h"
#include "lmk/search/scene_index.h"
#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/tabletop_scene.h"

namespace {

const lmk::SceneSettings& settings() {
  static const lmk::SceneSettings resolved = lmk::SceneSettings().resolved();
  return resolved;
}

// The frame as a search receives it: LMK_BENCH_FRAME's cloud, or a rendered tabletop frame
// (640 x 480, organised).
const lmk::PointCloud& raw_frame() {
  static const lmk::PointCloud raw = [] {
    const char* path = std::getenv("LMK_BENCH_FRAME");
    if (path && *path) return lmk::read_cloud(path);
    const lmk::SyntheticScene scene = lmk::make_tabletop_scene(1);
    return lmk::render_depth(scene.mesh, scene.T_world_sensor);
  }();
  return raw;
}

// The same frame as the index's parts read it, prepared as SceneIndex prepares it (veil points,
// depth smoothing).
const lmk::PointCloud& frame() {
  static const lmk::PointCloud prepared = [] {
    std::optional<lmk::PointCloud> ready = lmk::prepared_frame(
        raw_frame(), settings().veil_angle, settings().depth_smoothing, settings().depth_noise());
    return ready ? std::move(*ready) : raw_frame();
  }();
  return prepared;
}

const lmk::VoxelMoments& moments() {
  static const lmk::VoxelMoments built(frame(), settings().coarse_leaf);
  return built;
}

// Each benchmark's argument is the thread count TBB may use.
tbb::global_control threads_of(const benchmark::State& state) {
  return tbb::global_control(tbb::global_control::max_allowed_parallelism,
                             static_cast<std::size_t>(state.range(0)));
}

void BM_SceneIndex(benchmark::State& state) {
  const auto threads = threads_of(state);
  for (auto _ : state) benchmark::DoNotOptimize(lmk::SceneIndex(raw_frame(), settings()));
}

void BM_RangeImage(benchmark::State& state) {
  const auto threads = threads_of(state);
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        lmk::RangeImage::from_cloud(frame(), {}, lmk::kMaxIntrinsicsFitRms, nullptr));
  }
}

void BM_FinitePoints(benchmark::State& state) {
  const auto threads = threads_of(state);
  for (auto _ : state) benchmark::DoNotOptimize(lmk::remove_non_finite(frame()));
}

void BM_Occupancy(benchmark::State& state) {
  const auto threads = threads_of(state);
  for (auto _ : state) {
    benchmark::DoNotOptimize(lmk::OccupancyGrid(frame().points, settings().leaf_size));
  }
}

void BM_VoxelMoments(benchmark::State& state) {
  const auto threads = threads_of(state);
  for (auto _ : state) {
    const lmk::VoxelMoments built(frame(), settings().coarse_leaf);
    benchmark::DoNotOptimize(built.centroids());
  }
}

void BM_Normals(benchmark::State& state) {
  const auto threads = threads_of(state);
  for (auto _ : state) benchmark::DoNotOptimize(moments().normals(frame().sensor_origin()));
}

void BM_DistanceField(benchmark::State& state) {
  const auto threads = threads_of(state);
  const std::vector<Eigen::Vector3f> centroids = moments().centroids();
  const lmk::DistanceFieldSettings field{settings().coarse_leaf, *settings().field_band};
  for (auto _ : state) benchmark::DoNotOptimize(lmk::DistanceField(centroids, field));
}

}  // namespace

BENCHMARK(BM_SceneIndex)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RangeImage)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FinitePoints)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Occupancy)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_VoxelMoments)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Normals)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DistanceField)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
