// SPDX-License-Identifier: BSD-3-Clause
#include "tests/landmark/l_shape_scene.h"

#include "lmk/geometry/pose.h"
#include "lmk/sim/depth_sensor.h"

namespace lmk::test_scenes {

TriangleMesh l_shape() {
  TriangleMesh mesh;
  mesh.append(make_box_mesh({0.05, 0.05, 0.12}), pose_from_xyz_rpy({0, 0, 0.06}, {0, 0, 0}));
  mesh.append(make_box_mesh({0.10, 0.04, 0.04}), pose_from_xyz_rpy({0.075, 0, 0.02}, {0, 0, 0}));
  return mesh;
}

Eigen::Isometry3d capture_camera() {
  return camera_look_at({0, -0.8, kTable + 0.9}, {0, 0, kTable}, Eigen::Vector3d::UnitZ());
}

PointCloud render_on_table(TriangleMesh world, const Eigen::Isometry3d& camera) {
  world.append(make_box_mesh({1.4, 1.0, 0.04}),
               pose_from_xyz_rpy({0, 0, kTable - 0.02}, {0, 0, 0}));
  DepthSensorSettings sensor;
  sensor.noise = false;
  sensor.width = 320;  // a half-resolution sensor keeps the test fast; the geometry is the same
  sensor.height = 240;
  sensor.fx = sensor.fy = 262.5;
  sensor.cx = 159.5;
  sensor.cy = 119.5;
  return render_depth(world, camera, sensor);
}

PointCloud render_scene(const std::vector<Eigen::Vector2d>& positions, bool distractors,
                        const std::vector<Eigen::Isometry3d>& floating,
                        const Eigen::Isometry3d& camera) {
  TriangleMesh world;
  for (const auto& pose : floating) world.append(l_shape(), pose);
  for (const auto& xy : positions) {
    world.append(l_shape(), pose_from_xyz_rpy({xy.x(), xy.y(), kTable}, {0, 0, 0}));
  }
  if (distractors) {
    world.append(make_sphere_mesh(0.04), pose_from_xyz_rpy({-0.1, 0.25, kTable + 0.04}, {0, 0, 0}));
    world.append(make_cylinder_mesh(0.035, 0.12),
                 pose_from_xyz_rpy({0.15, 0.25, kTable + 0.06}, {0, 0, 0}));
    world.append(make_box_mesh({0.15, 0.1, 0.03}),
                 pose_from_xyz_rpy({0.4, 0.2, kTable + 0.015}, {0, 0, 0.3}));
  }
  return render_on_table(std::move(world), camera);
}

const std::vector<Eigen::Vector2d> kCopies = {{-0.45, -0.1}, {-0.1, -0.15}, {0.3, -0.05}};

Box box_at(const Eigen::Vector2d& xy) {
  const Eigen::Vector3d lo(xy.x() - 0.025 - 0.015, xy.y() - 0.025 - 0.015, kTable + 0.002);
  const Eigen::Vector3d hi(xy.x() + 0.125 + 0.015, xy.y() + 0.025 + 0.015, kTable + 0.12 + 0.015);
  return Box(pose_from_xyz_rpy(0.5 * (lo + hi), {0, 0, 0}), hi - lo);
}

}  // namespace lmk::test_scenes
