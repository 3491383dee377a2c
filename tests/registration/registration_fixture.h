// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A synthetic target for the registration tests: three faces of a box corner and a hemisphere on
// one of them, with exact normals. It constrains all six degrees of freedom. The samples are
// random, not on a lattice: on a lattice, point-to-point ICP has exact local minima one spacing
// apart.

#include <Eigen/Geometry>
#include <cmath>

#include "lmk/geometry/point_cloud.h"
#include "lmk/geometry/random.h"

namespace lmk::test {

inline PointCloud corner_with_bump() {
  PointCloud c;
  const auto add = [&](const Eigen::Vector3f& p, const Eigen::Vector3f& n) {
    c.points.push_back(p);
    c.normals.push_back(n.normalized());
  };
  SplitMix64 rng(17);
  for (int k = 0; k < 1600; ++k) {
    const auto uv = [&] { return 0.2f * static_cast<float>(rng.uniform01()); };
    add({uv(), uv(), 0.0f}, {0, 0, 1});
    add({uv(), 0.0f, uv()}, {0, 1, 0});
    add({0.0f, uv(), uv()}, {1, 0, 0});
  }
  const Eigen::Vector3f centre(0.12f, 0.12f, 0.0f);
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 40; ++j) {
      const float theta = 1.5f * i / 20.0f, phi = 6.2831853f * j / 40.0f;
      const Eigen::Vector3f n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                              std::cos(theta));
      add(centre + 0.04f * n, n);
    }
  c.set_unorganized();
  return c;
}

/// 8.6 degrees and 2.7 cm at scale 1.
inline Eigen::Isometry3d small_motion(double scale = 1.0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::AngleAxisd(0.15 * scale, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  T.translation() = scale * Eigen::Vector3d(0.02, -0.015, 0.01);
  return T;
}

}  // namespace lmk::test
