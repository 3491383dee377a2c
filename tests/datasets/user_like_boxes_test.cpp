// SPDX-License-Identifier: BSD-3-Clause
// The rule that draws landmark boxes on real frames: boxes go where a user would draw them, on the
// objects of a table top and never on bare table or floor, spread apart, inside the image.

#include "lmk/datasets/user_like_boxes.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/tabletop_scene.h"

namespace lmk {
namespace {

// The tabletop scene as its sensor sees it, in the camera frame.
struct CameraFrame {
  PointCloud cloud;
  PinholeIntrinsics intrinsics;
  SyntheticScene scene;
};

CameraFrame tabletop_in_camera(std::uint64_t seed) {
  CameraFrame f;
  f.scene = make_tabletop_scene(seed);
  DepthSensorSettings sensor;
  sensor.seed = seed;
  f.cloud = render_depth(f.scene.mesh, f.scene.T_world_sensor, sensor)
                .transformed(f.scene.T_world_sensor.inverse());
  f.intrinsics = {sensor.fx, sensor.fy, sensor.cx, sensor.cy};
  return f;
}

TEST(UserLikeBoxes, GoOnTheObjectsOfATableNotOnItsBareTop) {
  const CameraFrame f = tabletop_in_camera(3);
  UserBoxRule rule;
  rule.box_side = 0.15;
  const std::vector<Box> boxes = user_like_boxes(f.cloud, f.intrinsics, rule);
  ASSERT_FALSE(boxes.empty());
  EXPECT_LE(boxes.size(), rule.max_boxes);
  const double side = rule.box_side;
  const auto near_an_object = [&](const Eigen::Vector3d& world) {
    for (const SceneObject& o : f.scene.objects)
      if ((o.box.center() - world).norm() < side) return true;
    return false;
  };
  // Every object on the table is boxed (the most structured cells come first).
  for (const SceneObject& o : f.scene.objects) {
    EXPECT_TRUE(std::any_of(boxes.begin(), boxes.end(),
                            [&](const Box& b) {
                              return (f.scene.T_world_sensor * b.center() - o.box.center()).norm() <
                                     side;
                            }))
        << o.name << " has no box";
  }
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    // A box over the table top's interior (the 1.2 x 0.8 m top at 0.72 m, away from its rim) is
    // on an object: bare table top is never boxed. The rim and the leg are furniture edges.
    const Eigen::Vector3d c = f.scene.T_world_sensor * boxes[i].center();
    const bool over_top = std::abs(c.x()) < 0.6 - side && std::abs(c.y()) < 0.4 - side &&
                          std::abs(c.z() - 0.72) < side;
    if (over_top) {
      EXPECT_TRUE(near_an_object(c)) << "box " << i << " is on bare table top";
    }
    for (std::size_t j = 0; j < i; ++j)
      EXPECT_GE((boxes[i].center() - boxes[j].center()).norm(), side);
    EXPECT_EQ(boxes[i].size, Eigen::Vector3d::Constant(side));
  }
  // The same frame, the same boxes.
  const std::vector<Box> again = user_like_boxes(f.cloud, f.intrinsics, rule);
  ASSERT_EQ(again.size(), boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i)
    EXPECT_TRUE(again[i].pose.isApprox(boxes[i].pose, 0.0));
}

TEST(UserLikeBoxes, ABarePlaneGetsNone) {
  PointCloud wall;
  wall.width = 320;
  wall.height = 240;
  const PinholeIntrinsics k{300, 300, 160, 120};
  for (std::uint32_t v = 0; v < wall.height; ++v) {
    for (std::uint32_t u = 0; u < wall.width; ++u) {
      const double z = 1.5;
      wall.points.emplace_back((u - k.cx) * z / k.fx, (v - k.cy) * z / k.fy, z);
    }
  }
  EXPECT_TRUE(user_like_boxes(wall, k).empty());
}

}  // namespace
}  // namespace lmk
