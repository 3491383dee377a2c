// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Helpers for the robot tests (issue #60): the PR2 right arm's joint names, and a box as the
// points a sensor would see of it or as the triangles of its ground truth.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "lmk/geometry/point_cloud.h"
#include "lmk/geometry/solid.h"

namespace lmk::test {

/// The PR2 right arm's joints, shoulder to wrist.
inline const std::vector<std::string>& right_arm_joint_names() {
  static const std::vector<std::string> names = {"r_shoulder_pan_joint",   "r_shoulder_lift_joint",
                                                 "r_upper_arm_roll_joint", "r_elbow_flex_joint",
                                                 "r_forearm_roll_joint",   "r_wrist_flex_joint",
                                                 "r_wrist_roll_joint"};
  return names;
}

/// Points over the surface of an axis-aligned box of `size` at `centre` (base frame), `spacing`
/// apart.
inline PointCloud box_points(const Eigen::Vector3d& centre, const Eigen::Vector3d& size,
                             double spacing = 0.01) {
  PointCloud cloud;
  for (const Eigen::Vector3d& p : Solid::box(size).surface_points(spacing))
    cloud.points.push_back((p + centre).cast<float>());
  cloud.width = static_cast<std::uint32_t>(cloud.points.size());
  cloud.height = 1;
  return cloud;
}

/// The twelve triangles of an axis-aligned box of `size` at `centre`.
struct BoxMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
};
inline BoxMesh box_mesh(const Eigen::Vector3d& centre, const Eigen::Vector3d& size) {
  BoxMesh mesh;
  for (int k = 0; k < 8; ++k) {  // corner k: bit 0 x, bit 1 y, bit 2 z
    const Eigen::Vector3d sign((k & 1) ? 0.5 : -0.5, (k & 2) ? 0.5 : -0.5, (k & 4) ? 0.5 : -0.5);
    mesh.vertices.push_back(centre + sign.cwiseProduct(size));
  }
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    mesh.triangles.emplace_back(f[0], f[1], f[2]);
    mesh.triangles.emplace_back(f[0], f[2], f[3]);
  }
  return mesh;
}

}  // namespace lmk::test
