// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/pose.h"

#include <gtest/gtest.h>

#include "lmk/geometry/random.h"

namespace lmk {
namespace {

TEST(Pose, OrthonormalizedRepairsDriftAndKeepsTheRotation) {
  Eigen::Isometry3d T = pose_from_xyz_rpy({0.1, -0.2, 0.3}, {0.3, -0.5, 2.0});
  Eigen::Isometry3d drifted = T;
  drifted.linear() += 4e-6 * Eigen::Matrix3d::Ones();
  ASSERT_FALSE(is_valid_pose(drifted));
  const Eigen::Isometry3d repaired = orthonormalized(drifted);
  EXPECT_TRUE(is_valid_pose(repaired, 1e-12));
  EXPECT_LT(rotation_angle_between(repaired.linear(), T.linear()), 1e-5);
  EXPECT_EQ(repaired.translation(), T.translation());
}

TEST(Pose, RpyRoundTripsAwayFromGimbalLock) {
  SplitMix64 rng(1);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d rpy((rng.uniform01() - 0.5) * 2 * M_PI, (rng.uniform01() - 0.5) * 3.0,
                              (rng.uniform01() - 0.5) * 2 * M_PI);
    const Eigen::Isometry3d T = pose_from_xyz_rpy({1, 2, 3}, rpy);
    EXPECT_LT((rpy_from_rotation(T.linear()) - rpy).norm(), 1e-9);
    EXPECT_TRUE(is_valid_pose(T));
  }
}

TEST(Pose, RpyAtGimbalLockStillReproducesTheRotation) {
  const Eigen::Matrix3d R = pose_from_xyz_rpy({0, 0, 0}, {0.3, M_PI / 2, 0.2}).linear();
  const Eigen::Vector3d rpy = rpy_from_rotation(R);
  EXPECT_TRUE(pose_from_xyz_rpy({0, 0, 0}, rpy).linear().isApprox(R, 1e-9));
}

TEST(Pose, RotationAngleBetween) {
  const Eigen::Matrix3d a = pose_from_xyz_rpy({0, 0, 0}, {0.1, 0.2, 0.3}).linear();
  const Eigen::Matrix3d b =
      a * Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  EXPECT_NEAR(rotation_angle_between(a, b), 0.7, 1e-9);
  EXPECT_NEAR(rotation_angle_between(a, a), 0.0, 1e-6);
}

TEST(Pose, CameraLookAtPointsTheOpticalAxisAtTheTarget) {
  const Eigen::Vector3d eye(0, -1, 1.5), target(0.2, 0.3, 0.7);
  const Eigen::Isometry3d T = camera_look_at(eye, target, Eigen::Vector3d::UnitZ());
  EXPECT_TRUE(is_valid_pose(T));
  const Eigen::Vector3d in_camera = T.inverse() * target;
  EXPECT_NEAR(in_camera.x(), 0.0, 1e-12);
  EXPECT_NEAR(in_camera.y(), 0.0, 1e-12);
  EXPECT_GT(in_camera.z(), 0.0);
  // Image "down" (+y) points down in the world.
  EXPECT_LT(T.linear().col(1).z(), 0.0);
}

TEST(Pose, InvalidPoses) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation().x() = std::nan("");
  EXPECT_FALSE(is_valid_pose(T));
  T = Eigen::Isometry3d::Identity();
  T.linear().col(2) *= -1.0;  // a reflection
  EXPECT_FALSE(is_valid_pose(T));
}

}  // namespace
}  // namespace lmk
