// SPDX-License-Identifier: BSD-3-Clause
// Where the fast search seeds: near relief, and not on a bare floor whose normals only the sensor's
// noise scatters (detail/relief_seeds.h).
#include "lmk/search/fast/relief_seeds.h"

#include <gtest/gtest.h>

#include "lmk/geometry/pose.h"
#include "lmk/search/fast/point_pair_voting.h"
#include "lmk/search/scene_index.h"
#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/mesh.h"

namespace lmk {
namespace {

constexpr double kBlock = 0.2;  ///< side of the block on the floor, m

// A bare floor with one block on it, seen by the simulated Kinect from `distance` at 45 degrees,
// and indexed as a search indexes it.
SceneIndex floor_with_block(double distance) {
  TriangleMesh world;
  world.append(make_box_mesh({6.0, 6.0, 0.02}),
               Eigen::Isometry3d(Eigen::Translation3d(0.0, 0.0, -0.01)));
  world.append(make_box_mesh({kBlock, kBlock, kBlock}),
               Eigen::Isometry3d(Eigen::Translation3d(0.0, 0.0, 0.5 * kBlock)));
  const double reach = distance / std::sqrt(2.0);
  const Eigen::Isometry3d camera =
      camera_look_at({0.0, -reach, reach}, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
  return SceneIndex(render_depth(world, camera), SceneSettings{});
}

struct Shares {
  double floor = 0.0;  ///< of the floor's points well away from the block
  double block = 0.0;  ///< of the block's points (above the floor, over its footprint)
};

Shares near_relief_shares(const SceneIndex& index, bool with_sensor) {
  const PointCloud& cloud = index.coarse();
  detail::ReliefTest test;
  test.cell = 0.5 * kBlock * std::sqrt(3.0);  // as a search: half the landmark's diameter
  test.angle = detail::kCoplanarAngle;
  if (with_sensor) test.T_cloud_sensor = index.T_scene_sensor();
  std::vector<char> chosen(cloud.size(), 0);
  for (Index i : detail::points_near_relief(cloud, test)) chosen[i] = 1;
  std::size_t floor = 0, floor_chosen = 0, block = 0, block_chosen = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f& p = cloud.points[i];
    if (p.z() > 0.03f && p.head<2>().cwiseAbs().maxCoeff() < 0.6f * kBlock) {
      ++block;
      block_chosen += chosen[i];
    } else if (p.head<2>().norm() > 0.6f) {
      ++floor;
      floor_chosen += chosen[i];
    }
  }
  EXPECT_GT(floor, 1000u);
  EXPECT_GT(block, 50u);
  return {static_cast<double>(floor_chosen) / static_cast<double>(floor),
          static_cast<double>(block_chosen) / static_cast<double>(block)};
}

TEST(ReliefSeeds, ABareFloorAtRangeIsNoReliefWhenTheSensorsNoiseIsKnown) {
  // At 2.5 m the Kinect's depth levels are 2 cm apart: the floor's normals scatter.
  const SceneIndex index = floor_with_block(2.5);
  const Shares normals_only = near_relief_shares(index, false);
  const Shares noise_aware = near_relief_shares(index, true);
  EXPECT_GT(normals_only.floor, 0.3) << "the normals alone should mistake the floor for relief";
  EXPECT_LT(noise_aware.floor, 0.05);
  EXPECT_GT(noise_aware.block, 0.95);
}

TEST(ReliefSeeds, NearTheSensorTheBlockIsReliefAndTheFloorIsNot) {
  const Shares shares = near_relief_shares(floor_with_block(1.0), true);
  EXPECT_LT(shares.floor, 0.05);
  EXPECT_GT(shares.block, 0.95);
}

}  // namespace
}  // namespace lmk
