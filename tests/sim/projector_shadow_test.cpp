// SPDX-License-Identifier: BSD-3-Clause
// The projector's shadow as observed free space (geometry/projector_shadow.h): the rays through it
// end in space that is really empty, a no-return strip of the wrong width is not carved, and a
// landmark captured through a shadowing sensor keeps the free space a shadow-free one sees.

#include "lmk/geometry/projector_shadow.h"

#include <gtest/gtest.h>

#include "lmk/datasets/benchmark_dataset.h"
#include "lmk/geometry/pose.h"
#include "lmk/landmark/landmark.h"
#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/mesh.h"
#include "lmk/sim/scene_types.h"

namespace lmk {
namespace {

TEST(ProjectorShadow, RaysEndInFreeSpaceBesideTheShadowingObject) {
  DepthSensorSettings sensor;
  sensor.noise = false;
  TriangleMesh scene;
  scene.append(make_box_mesh({20.0, 20.0, 0.01}), pose_from_xyz_rpy({0, 0, 2.005}, {0, 0, 0}));
  const Box object(pose_from_xyz_rpy({0, 0, 1.0}, {0, 0, 0}), {0.2, 0.2, 0.2});
  scene.append(make_box_mesh(object.size), object.pose);
  const PointCloud cloud = render_depth(scene, Eigen::Isometry3d::Identity(), sensor);
  std::size_t no_return = 0;
  for (const auto& p : cloud.points) no_return += is_finite(p) ? 0 : 1;
  const std::vector<Eigen::Vector3f> ends = projector_shadow_ray_ends(cloud);
  // Every shadowed pixel beside the box (its rows), and nothing else.
  EXPECT_EQ(ends.size(), no_return);
  // Each ray is its pixel's: no return there, and the end on that pixel's line of sight.
  for (const ShadowRay& ray : projector_shadow_rays(cloud)) {
    ASSERT_FALSE(is_finite(cloud.points[ray.pixel]));
    const double u = static_cast<double>(ray.pixel % cloud.width);
    const double v = static_cast<double>(ray.pixel / cloud.width);
    EXPECT_NEAR(ray.end.x() / ray.end.z(), (u - sensor.cx) / sensor.fx, 1.0 / sensor.fx);
    EXPECT_NEAR(ray.end.y() / ray.end.z(), (v - sensor.cy) / sensor.fy, 1.0 / sensor.fy);
  }
  ASSERT_GT(ends.size(), 100u);
  for (const Eigen::Vector3f& end : ends) {
    EXPECT_LT(end.x(), -0.1 * end.z() / 0.9 + 1e-3);  // left of the box as the camera sees it
    EXPECT_GE(end.z(), 0.9 - 1e-6);                   // at least as deep as the box's front
    EXPECT_LE(end.z(), 2.0 + 1e-6);                   // not beyond the wall
    for (double t = 0.02; t <= 1.0; t += 0.02) {      // the camera's ray up to the end is empty
      const Eigen::Vector3d q = t * end.cast<double>();
      EXPECT_FALSE(object.contains(q)) << q.transpose();
    }
  }
}

TEST(ProjectorShadow, AStripOfTheWrongWidthIsNoShadow) {
  // One row of a hand-made frame: a wall at 2 m, 40 pixels without return, a box at 1 m. The
  // projector's shadow there would be 525 x 0.075 x (1/1 - 1/2) = 19.7 pixels wide: 40 is a dark
  // object's, not a shadow.
  PointCloud cloud;
  cloud.width = 100;
  cloud.height = 2;
  cloud.points.assign(200, Eigen::Vector3f::Constant(std::nanf("")));
  for (std::uint32_t v = 0; v < 2; ++v) {
    for (std::uint32_t u = 0; u < 100; ++u) {
      if (u >= 30 && u < 70) continue;
      const double z = u < 30 ? 2.0 : 1.0;
      cloud.points[v * 100 + u] = Eigen::Vector3f((u - 49.5) / 525.0 * z, 0.0f, z);
    }
  }
  EXPECT_TRUE(projector_shadow_ray_ends(cloud).empty());
  // The same strip 20 pixels wide is one.
  for (std::uint32_t v = 0; v < 2; ++v) {
    for (std::uint32_t u = 30; u < 50; ++u)
      cloud.points[v * 100 + u] = Eigen::Vector3f((u - 49.5) / 525.0 * 2.0, 0.0f, 2.0f);
  }
  EXPECT_EQ(projector_shadow_ray_ends(cloud).size(), 2u * 20u);
}

// The chair's backrest corner, captured in its demonstration scene: the shadow beside it would hide
// a fifth of its empty space; the rays through the shadow give it back.
TEST(ProjectorShadow, CaptureKeepsTheFreeSpaceAShadowHides) {
  const auto& landmarks = benchmark_landmarks();
  const auto chair =
      std::find_if(landmarks.begin(), landmarks.end(),
                   [](const BenchmarkLandmark& l) { return l.name == "chair_corner"; });
  ASSERT_NE(chair, landmarks.end());
  const GeneratedScene demo = make_scene(chair->demo_scene, 0, false);
  const Box box = demo.instances.at(chair->name).front();
  DepthSensorSettings sensor;
  sensor.flying_pixel_rate = 0.0;
  const PointCloud shadowed = render_depth(demo.mesh, demo.T_world_sensor, sensor);
  sensor.shadows = false;
  const PointCloud unshadowed = render_depth(demo.mesh, demo.T_world_sensor, sensor);
  CaptureSettings settings;
  settings.base_frame = true;
  const std::size_t reference = capture(unshadowed, box, "c", settings).empty_space.size();
  const std::size_t through_shadow = capture(shadowed, box, "c", settings).empty_space.size();
  settings.projector_baseline = 0.0;
  const std::size_t without = capture(shadowed, box, "c", settings).empty_space.size();
  EXPECT_LT(static_cast<double>(without), 0.85 * static_cast<double>(reference));
  EXPECT_GT(static_cast<double>(through_shadow), 0.97 * static_cast<double>(reference));
  EXPECT_LE(through_shadow,
            reference + reference / 100);  // nothing a shadow-free view calls occupied
}

}  // namespace
}  // namespace lmk
