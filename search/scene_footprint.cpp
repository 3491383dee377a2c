// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/scene_footprint.h"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <vector>

#include "lmk/geometry/error.h"
#include "lmk/geometry/internal/voxel_key.h"
#include "lmk/geometry/internal/voxel_table.h"
#include "lmk/landmark/scene_settings.h"

namespace lmk {
namespace {

// What each counted thing costs at SceneIndex's peak, with a search in it, bytes: the grids' node
// sizes from OpenVDB's layout, the rest fitted to the peaks measured on six scenes (surfaces of 1
// and 5 million points, points scattered through 3 m and 40 m, a 5-million-point cube, a rendered
// frame; scene_footprint_test.cpp) and rounded up. The stages free their temporaries before the
// next begins, so a sum of every part is an upper bound: the estimate came out 1.2-1.4 times the
// measured peak (2 on the small frame, whose fixed part dominates).
constexpr double kFixedBytes = 16e6;       // the search's candidates and thread scratch
constexpr double kPerPointBytes = 40.0;    // beside the point's copy: voxel buckets, fine level
constexpr double kPerCoarseVoxel = 160.0;  // moments, centroid, normal, tree, seeds' features
// An OpenVDB tree (5, 4, 3): leaves of 8^3 voxels under lower nodes of 16^3 leaves under upper
// nodes of 32^3 lower nodes. A scattered scene's leaves each need their own lower node, whose
// 4096 child slots cost more than the leaf itself: the nodes of every level are counted.
constexpr std::int64_t kLeafSide = 8;
// The distance field's two grids (float distances, int32 closest points) and, while a slab is
// built, a 64-bit key per voxel.
constexpr double kFieldLeafBytes = 2 * (512 * 4 + 160) + 512 * 8;
constexpr double kFieldLowerBytes = 2 * (4096 * 8 + 2 * 512 + 64);
constexpr double kFieldUpperBytes = 2 * (32768 * 8 + 2 * 4096 + 64);
// The occupancy grid: booleans, a bit each.
constexpr double kOccupancyLeafBytes = 2 * 64 + 96;
constexpr double kOccupancyLowerBytes = 4096 * 8 + 2 * 512 + 64;
constexpr double kOccupancyUpperBytes = 32768 * 8 + 2 * 4096 + 64;
// A prepared organised frame is a copy of the scene; its range image a float per pixel.
constexpr double kPerRangePixel = 8.0;

struct TreeNodes {
  std::size_t leaves = 0, lower = 0, upper = 0;
};

double price(const TreeNodes& n, double leaf, double lower, double upper) {
  return static_cast<double>(n.leaves) * leaf + static_cast<double>(n.lower) * lower +
         static_cast<double>(n.upper) * upper;
}

double bytes_per_point(const PointCloud& c) {
  double b = sizeof(Eigen::Vector3f);
  if (!c.normals.empty()) b += sizeof(Eigen::Vector3f);
  if (!c.colors.empty()) b += sizeof(Color);
  if (!c.labels.empty()) b += sizeof(std::int32_t);
  return b;
}

std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

detail::VoxelCoord unpack_voxel(std::uint64_t key) {
  constexpr std::uint64_t mask = (std::uint64_t{1} << detail::kVoxelKeyBits) - 1;
  detail::VoxelCoord c;
  for (int a = 2; a >= 0; --a) {
    c[static_cast<std::size_t>(a)] =
        static_cast<std::int64_t>(key & mask) - detail::kVoxelKeyOffset;
    key >>= detail::kVoxelKeyBits;
  }
  return c;
}

// Into `keys`: the voxel (side 1 / inv_leaf) of every finite point of `scene` inside the work
// volume, when there is one: the points a SceneIndex keeps.
void voxel_keys(const PointCloud& scene, const std::optional<Box>& work_volume, double inv_leaf,
                std::vector<std::uint64_t>& keys) {
  keys.clear();
  keys.reserve(scene.size());
  for (const Eigen::Vector3f& p : scene.points) {
    if (!p.allFinite() || (work_volume && !work_volume->contains(p))) continue;
    keys.push_back(detail::pack_voxel(detail::voxel_coord(p, inv_leaf)));
  }
}

// Sorts `keys` and returns how many differ.
std::size_t count_distinct(std::vector<std::uint64_t>& keys) {
  tbb::parallel_sort(keys.begin(), keys.end());
  return static_cast<std::size_t>(std::unique(keys.begin(), keys.end()) - keys.begin());
}

// The nodes of every level of a tree holding the leaves `keys` (packed leaf coordinates, in any
// order, repeats allowed; `keys` is used up).
TreeNodes tree_nodes(std::vector<std::uint64_t>& keys) {
  TreeNodes n;
  const auto parents = [&keys](std::int64_t children_per_side) {
    for (std::uint64_t& key : keys) {
      detail::VoxelCoord c = unpack_voxel(key);
      for (std::int64_t& v : c) v = floor_div(v, children_per_side);
      key = detail::pack_voxel(c);
    }
    keys.resize(count_distinct(keys));
    return keys.size();
  };
  keys.resize(count_distinct(keys));
  n.leaves = keys.size();
  n.lower = parents(16);
  n.upper = parents(32);
  return n;
}

}  // namespace

std::size_t available_memory() {
  std::ifstream meminfo("/proc/meminfo");
  for (std::string key; meminfo >> key;) {
    unsigned long long kb = 0;
    if (key == "MemAvailable:" && meminfo >> kb) return static_cast<std::size_t>(kb) * 1024;
    meminfo.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  return std::numeric_limits<std::size_t>::max();
}

void require_footprint_fits(const PointCloud& scene, const SceneSettings& settings) {
  const std::size_t available = available_memory();
  const SceneFootprint f = estimate_scene_footprint(scene, settings, available);
  if (!f.over_limit) return;
  throw Error("scene: indexing it would take over " + describe_bytes(f.bytes) + " (" +
              std::to_string(f.points) + " points in " + std::to_string(f.coarse_voxels) +
              " coarse voxels), more than the " + describe_bytes(available) +
              " this machine has available; crop it (--work-volume) or use a coarser leaf "
              "(--coarse-leaf)");
}

std::string describe_bytes(std::size_t bytes) {
  char text[32];
  const double b = static_cast<double>(bytes);
  if (b >= 1e9) {
    std::snprintf(text, sizeof(text), "%.2f GB", b / 1e9);
  } else {
    std::snprintf(text, sizeof(text), "%.0f MB", std::ceil(b / 1e6));
  }
  return text;
}

SceneFootprint estimate_scene_footprint(const PointCloud& scene, const SceneSettings& settings,
                                        std::size_t limit) {
  validate(settings);
  const SceneSettings r = settings.resolved();
  SceneFootprint f;
  const double point_bytes = bytes_per_point(scene);
  double bytes = kFixedBytes;
  // An organised frame is prepared into a copy and projected into a range image of its pixels.
  if (scene.is_organized()) {
    bytes += static_cast<double>(scene.size()) * (point_bytes + kPerRangePixel);
  }
  const auto over = [&] {
    f.bytes = bytes >= static_cast<double>(std::numeric_limits<std::size_t>::max())
                  ? std::numeric_limits<std::size_t>::max()
                  : static_cast<std::size_t>(bytes);
    f.over_limit = f.bytes > limit;
    return f.over_limit;
  };

  // The coarse voxels of the finite points inside the work volume.
  std::vector<std::uint64_t> keys;
  voxel_keys(scene, r.work_volume, 1.0 / r.coarse_leaf, keys);
  f.points = keys.size();
  bytes += static_cast<double>(f.points) * (kPerPointBytes + point_bytes);
  keys.resize(count_distinct(keys));
  f.coarse_voxels = keys.size();
  bytes += static_cast<double>(f.coarse_voxels) * kPerCoarseVoxel;
  if (over()) return f;

  // The field's leaf nodes: each coarse voxel's band, in nodes of 8 voxels a side. The keys are
  // sorted, so neighbours mostly repeat the node just counted; the table grows only with the
  // nodes, and counting stops once they alone pass the limit.
  const std::int64_t reach = static_cast<std::int64_t>(std::ceil(*r.field_band / r.coarse_leaf));
  detail::VoxelTable table(f.coarse_voxels / 64 + 1);
  std::vector<std::uint64_t> leaves;
  std::uint64_t last = detail::kNoVoxel;
  for (const std::uint64_t key : keys) {
    const detail::VoxelCoord v = unpack_voxel(key);
    detail::VoxelCoord lo, hi;
    for (std::size_t a = 0; a < 3; ++a) {
      lo[a] = floor_div(v[a] - reach, kLeafSide);
      hi[a] = floor_div(v[a] + reach, kLeafSide);
    }
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
          const std::uint64_t node = detail::pack_voxel({x, y, z});
          if (node == last) continue;
          last = node;
          const std::size_t before = table.size();
          table.insert(node);
          if (table.size() > before) leaves.push_back(node);
        }
      }
    }
    if (static_cast<double>(leaves.size()) * kFieldLeafBytes + bytes > static_cast<double>(limit)) {
      break;
    }
  }
  f.field_nodes = leaves.size();
  bytes += price(tree_nodes(leaves), kFieldLeafBytes, kFieldLowerBytes, kFieldUpperBytes);
  if (over()) return f;

  // The occupancy grid's leaf nodes: voxels of the paper's leaf, 8 a side.
  voxel_keys(scene, r.work_volume, 1.0 / (kLeafSide * r.leaf_size), keys);
  const TreeNodes occupancy = tree_nodes(keys);
  f.occupancy_nodes = occupancy.leaves;
  bytes += price(occupancy, kOccupancyLeafBytes, kOccupancyLowerBytes, kOccupancyUpperBytes);
  over();
  return f;
}

}  // namespace lmk
