// SPDX-License-Identifier: BSD-3-Clause
// The paper's 17 scene types: each builds, is deterministic, holds its in-context landmarks where
// the ground truth says, and the hard variant really rotates what the paper could not handle.

#include "lmk/sim/scene_types.h"

#include <gtest/gtest.h>

#include <set>

#include "lmk/geometry/error.h"
#include "lmk/geometry/filters.h"
#include "lmk/geometry/pose.h"

namespace lmk {
namespace {

TEST(SceneTypes, TheSeventeenScenesOfThePaperInTheirSettings) {
  ASSERT_EQ(scene_types().size(), 17u);
  std::map<std::string, int> per_setting;
  for (const std::string& type : scene_types()) ++per_setting[make_scene(type, 0).setting];
  EXPECT_EQ(per_setting["simple"], 4);
  EXPECT_EQ(per_setting["cluttered"], 6);
  EXPECT_EQ(per_setting["unconventional"], 7);
  EXPECT_THROW(make_scene("simple/nothing", 0), Error);
}

TEST(SceneTypes, EveryLandmarkHasADemonstrationSceneThatHoldsIt) {
  std::set<std::string> names;
  for (const BenchmarkLandmark& landmark : benchmark_landmarks()) {
    names.insert(landmark.name);
    const GeneratedScene demo = make_scene(landmark.demo_scene, 0);
    EXPECT_EQ(demo.setting, landmark.setting);
    ASSERT_TRUE(demo.instances.count(landmark.name)) << landmark.name;
    EXPECT_FALSE(demo.instances.at(landmark.name).empty()) << landmark.name;
  }
  // Every in-context name is a benchmark landmark.
  for (const std::string& type : scene_types()) {
    for (const std::string& name : make_scene(type, 0).in_context) {
      EXPECT_TRUE(names.count(name)) << type << ": " << name;
    }
  }
}

TEST(SceneTypes, GroundTruthBoxesHoldWhatTheSensorSees) {
  // In every scene, each ground-truth box of an in-context landmark holds visible surface: the
  // sensor pose is honoured and the instances are where the labels say.
  for (const std::string& type : scene_types()) {
    const GeneratedScene scene = make_scene(type, 1);
    const PointCloud cloud = render_scene(scene);
    EXPECT_EQ(cloud.T_cloud_sensor.matrix(), scene.T_world_sensor.matrix());
    for (const std::string& name : scene.in_context) {
      if (!scene.instances.count(name)) continue;  // e.g. mounts in a full rack: all hidden
      for (const Box& box : scene.instances.at(name)) {
        EXPECT_GE(indices_in_box(cloud, box).size(), 30u)
            << type << ": " << name << " at " << box.center().transpose();
      }
    }
  }
}

TEST(SceneTypes, DeterministicPerSeedAndVariedAcrossSeeds) {
  for (const std::string& type :
       {std::string("cluttered/shelf"), std::string("unconventional/chair")}) {
    const GeneratedScene a = make_scene(type, 5), b = make_scene(type, 5), c = make_scene(type, 6);
    EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
    EXPECT_EQ(a.T_world_sensor.matrix(), b.T_world_sensor.matrix());
    EXPECT_NE(a.T_world_sensor.matrix(), c.T_world_sensor.matrix());
  }
}

TEST(SceneTypes, HardScenesRotateChairsAndTiltWalls) {
  double largest_chair_yaw = 0.0, largest_rack_tilt = 0.0;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    const GeneratedScene chair = make_scene("unconventional/chair", seed, true);
    const Box& corner = chair.instances.at("chair_corner").front();
    const Eigen::Vector3d x = corner.pose.linear().col(0);
    largest_chair_yaw = std::max(largest_chair_yaw, std::abs(std::atan2(x.y(), x.x())));
    const GeneratedScene rack = make_scene("unconventional/rack_partly_full", seed, true);
    const Eigen::Vector3d z = rack.instances.at("griple_mount").front().pose.linear().col(2);
    largest_rack_tilt = std::max(largest_rack_tilt, std::acos(std::min(1.0, z.z())));
  }
  EXPECT_GT(largest_chair_yaw, 1.0);   // beyond 57 degrees
  EXPECT_GT(largest_rack_tilt, 0.35);  // beyond 20 degrees
  const GeneratedScene easy = make_scene("unconventional/chair", 3, false);
  const Eigen::Vector3d x = easy.instances.at("chair_corner").front().pose.linear().col(0);
  EXPECT_LT(std::abs(std::atan2(x.y(), x.x())), 0.2);
}

}  // namespace
}  // namespace lmk
