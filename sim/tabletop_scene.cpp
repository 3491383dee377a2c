// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/sim/tabletop_scene.h"

#include "lmk/geometry/pose.h"
#include "lmk/geometry/random.h"

namespace lmk {
namespace {

constexpr double kTableHeight = 0.72;
const Eigen::Vector3d kTableSize(1.2, 0.8, 0.04);

void place(SyntheticScene& scene, const std::string& name, const TriangleMesh& mesh,
           const Eigen::Vector3d& size, const Eigen::Vector2d& xy, double yaw) {
  // Resting on the table: the object's centre is half its height above the top.
  const Eigen::Isometry3d T_world_object = pose_from_xyz_rpy(
      Eigen::Vector3d(xy.x(), xy.y(), kTableHeight + 0.5 * size.z()), Eigen::Vector3d(0, 0, yaw));
  scene.mesh.append(mesh, T_world_object);
  scene.objects.push_back({name, Box(T_world_object, size)});
}

}  // namespace

SyntheticScene make_tabletop_scene(std::uint64_t seed) {
  SplitMix64 rng(seed);
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * rng.uniform01(); };
  SyntheticScene scene;

  // Table: top and one central leg, so that the floor behind it is partly occluded.
  scene.mesh.append(make_box_mesh(kTableSize),
                    pose_from_xyz_rpy({0, 0, kTableHeight - 0.5 * kTableSize.z()}, {0, 0, 0}));
  scene.mesh.append(make_box_mesh({0.08, 0.08, kTableHeight - kTableSize.z()}),
                    pose_from_xyz_rpy({0, 0, 0.5 * (kTableHeight - kTableSize.z())}, {0, 0, 0}));
  scene.mesh.append(make_box_mesh({4.0, 4.0, 0.02}), pose_from_xyz_rpy({0, 0, -0.01}, {0, 0, 0}));

  // Objects in three lanes across the table, so that they never overlap.
  const Eigen::Vector3d carton(0.07, 0.07, 0.19), cup(0.08, 0.08, 0.10), ball(0.065, 0.065, 0.065);
  place(scene, "carton", make_box_mesh(carton), carton,
        {uniform(-0.45, -0.25), uniform(-0.25, 0.25)}, uniform(0, 2 * M_PI));
  place(scene, "cup", make_cylinder_mesh(0.5 * cup.x(), cup.z()), cup,
        {uniform(-0.1, 0.1), uniform(-0.25, 0.25)}, uniform(0, 2 * M_PI));
  place(scene, "ball", make_sphere_mesh(0.5 * ball.x()), ball,
        {uniform(0.25, 0.45), uniform(-0.25, 0.25)}, 0.0);

  // A head-mounted sensor in front of the table, about 1.3 m up, looking at the table top.
  const Eigen::Vector3d eye(uniform(-0.2, 0.2), -1.1 + uniform(-0.1, 0.1),
                            1.3 + uniform(-0.1, 0.1));
  scene.T_world_sensor = camera_look_at(eye, {0, 0, kTableHeight}, Eigen::Vector3d::UnitZ());
  return scene;
}

}  // namespace lmk
