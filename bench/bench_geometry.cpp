// SPDX-License-Identifier: BSD-3-Clause
// Voxel downsampling and k-d tree build/query on a 640x480 frame: lmk against PCL's VoxelGrid and
// KdTreeFLANN, on the same rendered tabletop frame (sim/tabletop_scene.h), in the same run.
//
//   build/bench/bench_geometry                       # all
//   build/bench/bench_geometry --benchmark_filter=Voxel

#include <benchmark/benchmark.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include "lmk/geometry/filters.h"
#include "lmk/geometry/kdtree.h"
#include "lmk/geometry/voxel_grid.h"
#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/tabletop_scene.h"

namespace {

constexpr double kLeaf = 0.005;  // the paper's leaf size

// One rendered Kinect frame (640 x 480, organised, with NaNs), shared by every benchmark.
const lmk::PointCloud& frame() {
  static const lmk::PointCloud cloud = [] {
    const lmk::SyntheticScene scene = lmk::make_tabletop_scene(1);
    return lmk::render_depth(scene.mesh, scene.T_world_sensor);
  }();
  return cloud;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr to_pcl(const lmk::PointCloud& cloud) {
  auto out = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  for (const auto& p : cloud.points) {
    if (lmk::is_finite(p)) out->push_back({p.x(), p.y(), p.z()});
  }
  return out;
}

// Query points: a fixed sample of the frame, nudged off the surface by 2 mm.
std::vector<Eigen::Vector3f> queries(const lmk::PointCloud& cloud, std::size_t n) {
  std::vector<Eigen::Vector3f> out;
  for (const auto& p : lmk::random_sample(cloud, n, 7).points)
    out.push_back(p + Eigen::Vector3f::Constant(0.002f));
  return out;
}

void BM_VoxelDownsample_lmk(benchmark::State& state) {
  const lmk::PointCloud& cloud = frame();
  for (auto _ : state) benchmark::DoNotOptimize(lmk::voxel_downsample(cloud, kLeaf));
  state.counters["points_in"] = static_cast<double>(cloud.count_finite());
  state.counters["points_out"] = static_cast<double>(lmk::voxel_downsample(cloud, kLeaf).size());
}

void BM_VoxelDownsample_pcl(benchmark::State& state) {
  const auto cloud = to_pcl(frame());
  pcl::VoxelGrid<pcl::PointXYZ> grid;
  grid.setLeafSize(kLeaf, kLeaf, kLeaf);
  grid.setInputCloud(cloud);
  pcl::PointCloud<pcl::PointXYZ> out;
  for (auto _ : state) {
    grid.filter(out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["points_out"] = static_cast<double>(out.size());
}

// state.range(0): 0 = the full frame, 1 = the frame downsampled at 5 mm (what the search uses).
lmk::PointCloud bench_cloud(const benchmark::State& state) {
  return state.range(0) == 0 ? lmk::remove_non_finite(frame())
                             : lmk::voxel_downsample(frame(), kLeaf);
}

void BM_KdTreeBuild_lmk(benchmark::State& state) {
  const lmk::PointCloud cloud = bench_cloud(state);
  for (auto _ : state) benchmark::DoNotOptimize(lmk::KdTree(cloud).size());
  state.counters["points"] = static_cast<double>(cloud.size());
}

void BM_KdTreeBuild_pcl(benchmark::State& state) {
  const auto cloud = to_pcl(bench_cloud(state));
  for (auto _ : state) {
    pcl::KdTreeFLANN<pcl::PointXYZ> tree;
    tree.setInputCloud(cloud);
    benchmark::DoNotOptimize(&tree);
  }
}

// state.range(1): neighbours per query. Reports time per query.
void BM_KdTreeKnn_lmk(benchmark::State& state) {
  const lmk::PointCloud cloud = bench_cloud(state);
  const lmk::KdTree tree(cloud);
  const auto q = queries(frame(), 1000);
  std::vector<lmk::Neighbor> out;
  for (auto _ : state) {
    for (const auto& p : q) tree.knn(p, static_cast<std::size_t>(state.range(1)), out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(q.size()));
}

void BM_KdTreeKnn_pcl(benchmark::State& state) {
  const auto cloud = to_pcl(bench_cloud(state));
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(cloud);
  const auto q = queries(frame(), 1000);
  const int k = static_cast<int>(state.range(1));
  std::vector<int> idx(k);
  std::vector<float> d2(k);
  for (auto _ : state) {
    for (const auto& p : q) tree.nearestKSearch(pcl::PointXYZ(p.x(), p.y(), p.z()), k, idx, d2);
    benchmark::DoNotOptimize(idx.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(q.size()));
}

void BM_KdTreeRadius_lmk(benchmark::State& state) {
  const lmk::KdTree tree(bench_cloud(state));
  const auto q = queries(frame(), 1000);
  for (auto _ : state) {
    for (const auto& p : q) benchmark::DoNotOptimize(tree.radius(p, 0.01f));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(q.size()));
}

void BM_KdTreeRadius_pcl(benchmark::State& state) {
  const auto cloud = to_pcl(bench_cloud(state));
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(cloud);
  const auto q = queries(frame(), 1000);
  std::vector<int> idx;
  std::vector<float> d2;
  for (auto _ : state) {
    for (const auto& p : q) tree.radiusSearch(pcl::PointXYZ(p.x(), p.y(), p.z()), 0.01, idx, d2);
    benchmark::DoNotOptimize(idx.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(q.size()));
}

BENCHMARK(BM_VoxelDownsample_lmk)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_VoxelDownsample_pcl)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KdTreeBuild_lmk)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KdTreeBuild_pcl)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KdTreeKnn_lmk)
    ->Args({0, 1})
    ->Args({1, 1})
    ->Args({1, 20})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_KdTreeKnn_pcl)
    ->Args({0, 1})
    ->Args({1, 1})
    ->Args({1, 20})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_KdTreeRadius_lmk)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_KdTreeRadius_pcl)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
