// SPDX-License-Identifier: BSD-3-Clause
// Solid primitives (solid.h): signed distances against hand-worked points, surface points on the
// surface, spheres that cover what they are given.

#include "lmk/geometry/solid.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lmk/geometry/error.h"

namespace lmk {
namespace {

TEST(Solid, SignedDistancesOfABoxACylinderAndASphere) {
  const Solid box = Solid::box({0.2, 0.4, 0.6});
  EXPECT_NEAR(box.signed_distance({0, 0, 0}), -0.1, 1e-12);   // the nearest face is x's
  EXPECT_NEAR(box.signed_distance({0.3, 0, 0}), 0.2, 1e-12);  // 0.2 beyond the x face
  EXPECT_NEAR(box.signed_distance({0.4, 0.5, 0}), std::hypot(0.3, 0.3), 1e-12);  // off an edge
  const Solid can = Solid::cylinder(0.05, 0.2);
  EXPECT_NEAR(can.signed_distance({0, 0, 0}), -0.05, 1e-12);
  EXPECT_NEAR(can.signed_distance({0.08, 0, 0}), 0.03, 1e-12);  // beside the wall
  EXPECT_NEAR(can.signed_distance({0, 0, 0.15}), 0.05, 1e-12);  // above the lid
  EXPECT_NEAR(can.signed_distance({0.08, 0, 0.14}), std::hypot(0.03, 0.04), 1e-12);  // off the rim
  const Solid ball = Solid::sphere(0.1);
  EXPECT_NEAR(ball.signed_distance({0, 0.3, 0}), 0.2, 1e-12);
  EXPECT_NEAR(ball.bounding_radius(), 0.1, 1e-12);
  EXPECT_NEAR(box.bounding_radius(), 0.5 * std::sqrt(0.04 + 0.16 + 0.36), 1e-12);
  EXPECT_NEAR(can.bounding_radius(), std::hypot(0.05, 0.1), 1e-12);
}

TEST(Solid, SurfacePointsLieOnTheSurfaceAndCoverIt) {
  for (const Solid& s :
       {Solid::box({0.2, 0.1, 0.3}), Solid::cylinder(0.04, 0.3), Solid::sphere(0.07)}) {
    const std::vector<Eigen::Vector3d> points = s.surface_points(0.01);
    ASSERT_GT(points.size(), 50u);
    for (const Eigen::Vector3d& p : points) EXPECT_NEAR(s.signed_distance(p), 0.0, 1e-9);
    // Every surface point a random direction reaches has a sample within the spacing's reach.
    for (int k = 0; k < 50; ++k) {
      const Eigen::Vector3d dir = Eigen::Vector3d::Random().normalized();
      // March from outside in until the surface.
      double t = s.bounding_radius() + 0.01;
      while (s.signed_distance(t * dir) > 1e-6) t -= std::max(s.signed_distance(t * dir), 1e-6);
      double nearest = 1.0;
      for (const Eigen::Vector3d& p : points) nearest = std::min(nearest, (p - t * dir).norm());
      EXPECT_LT(nearest, 0.01) << "kind " << static_cast<int>(s.kind());
    }
  }
}

TEST(Solid, BadSizesAreRefused) {
  EXPECT_THROW(Solid::box({0.1, 0.0, 0.1}), Error);
  EXPECT_THROW(Solid::cylinder(-1.0, 0.1), Error);
  EXPECT_THROW(Solid::sphere(std::nan("")), Error);
  EXPECT_THROW(Solid::sphere(0.1).surface_points(0.0), Error);
}

TEST(CoverWithSpheres, EveryPointIsInsideASphereAndNoneReachesFar) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 2000; ++i) points.push_back(0.2 * Eigen::Vector3d::Random());
  const double cell = 0.03;
  const std::vector<CoveringSphere> spheres = cover_with_spheres(points, cell);
  ASSERT_FALSE(spheres.empty());
  for (const Eigen::Vector3d& p : points) {
    bool inside = false;
    for (const CoveringSphere& s : spheres) inside |= (p - s.centre).norm() <= s.radius + 1e-12;
    EXPECT_TRUE(inside);
  }
  for (const CoveringSphere& s : spheres) EXPECT_LE(s.radius, cell * std::sqrt(3.0) / 2 + 1e-12);
}

}  // namespace
}  // namespace lmk
