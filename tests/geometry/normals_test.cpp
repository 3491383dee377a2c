// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/normals.h"

#include <gtest/gtest.h>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/random.h"

namespace lmk {
namespace {

// A tilted plane patch seen from a sensor on one side of it.
PointCloud tilted_plane(const Eigen::Vector3d& normal, std::uint64_t seed) {
  const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), normal);
  SplitMix64 rng(seed);
  PointCloud cloud;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d local(rng.uniform01() - 0.5, rng.uniform01() - 0.5, 0.0);
    cloud.points.push_back((q * local).cast<float>());
  }
  cloud.set_unorganized();
  return cloud;
}

TEST(Normals, PlaneNormalsMatchThePlaneAndFaceTheSensor) {
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, -0.4, 0.8).normalized();
  for (const double side : {1.0, -1.0}) {
    PointCloud cloud = tilted_plane(n, 3);
    cloud.T_cloud_sensor.translation() = side * 2.0 * n;
    compute_normals(cloud, {15});
    for (const auto& normal : cloud.normals) {
      ASSERT_TRUE(is_finite(normal));
      EXPECT_NEAR(normal.cast<double>().dot(side * n), 1.0, 1e-4);
    }
  }
}

TEST(Normals, SphereNormalsAreRadialAndFaceAnInsideSensor) {
  SplitMix64 rng(4);
  PointCloud cloud;
  for (int i = 0; i < 5000; ++i) {
    Eigen::Vector3d d(rng.normal(), rng.normal(), rng.normal());
    cloud.points.push_back((0.5 * d.normalized()).cast<float>());
  }
  cloud.set_unorganized();
  compute_normals(cloud, {10});  // sensor at the centre: normals point inwards
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_LT(cloud.normals[i].dot(cloud.points[i].normalized()), -0.99f);
  }
}

TEST(Normals, UndefinedWhereThePointIsNaNOrTheNeighbourhoodIsALine) {
  PointCloud line;
  for (int i = 0; i < 20; ++i) line.points.emplace_back(0.01f * i, 0.0f, 0.0f);
  line.points.emplace_back(std::nanf(""), 0.0f, 0.0f);
  line.set_unorganized();
  compute_normals(line, {5});
  for (const auto& n : line.normals) EXPECT_FALSE(is_finite(n));
  EXPECT_THROW(compute_normals(line, {2}), Error);
}

}  // namespace
}  // namespace lmk
