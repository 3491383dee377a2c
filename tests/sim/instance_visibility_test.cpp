// SPDX-License-Identifier: BSD-3-Clause
// Instance visibility and viewpoints, the ground truth of the range, viewpoint and occlusion
// benchmarks: a captured landmark is seen whole where it was captured, not at all behind a wall,
// about half behind half a wall; viewpoints keep to their ranges and look at their target.

#include "lmk/sim/instance_visibility.h"

#include <gtest/gtest.h>

#include "lmk/geometry/pose.h"
#include "lmk/sim/mesh.h"

namespace lmk {
namespace {

class InstanceVisibility : public ::testing::Test {
 protected:
  void SetUp() override {
    sensor_.noise = false;
    world_.append(make_box_mesh({4.0, 4.0, 0.02}), pose_from_xyz_rpy({0, 0, -0.01}, {0, 0, 0}));
    world_.append(make_box_mesh({0.2, 0.15, 0.3}), pose_from_xyz_rpy({0, 0, 0.15}, {0, 0, 0.4}));
    T_world_sensor_ = camera_look_at({0.2, -1.3, 1.2}, {0, 0, 0.15}, Eigen::Vector3d::UnitZ());
    box_ = Box(pose_from_xyz_rpy({0, 0, 0.16}, {0, 0, 0.4}), {0.3, 0.25, 0.34});
    CaptureSettings settings;
    settings.base_frame = true;
    landmark_ = capture(render_depth(world_, T_world_sensor_, sensor_), box_, "block", settings);
  }
  double hidden_behind(const TriangleMesh& occluder) const {
    TriangleMesh world = world_;
    world.append(occluder);
    return hidden_fraction(landmark_, box_, render_depth(world, T_world_sensor_, sensor_), sensor_);
  }
  DepthSensorSettings sensor_;
  TriangleMesh world_;
  Eigen::Isometry3d T_world_sensor_;
  Box box_;
  Landmark landmark_;
};

TEST_F(InstanceVisibility, SeenWholeWhereItWasCaptured) {
  EXPECT_LT(hidden_behind(TriangleMesh()), 0.05);
}

TEST_F(InstanceVisibility, HiddenBehindAWallAndHalfBehindHalfAWall) {
  // A screen halfway between the sensor and the block, across the whole view of it.
  const Eigen::Vector3d middle =
      0.5 * (T_world_sensor_.translation() + Eigen::Vector3d(0, 0, 0.15));
  TriangleMesh wall;
  wall.append(make_box_mesh({1.0, 0.01, 1.0}), pose_from_xyz_rpy(middle, {0, 0, 0}));
  EXPECT_GT(hidden_behind(wall), 0.95);
  // Half of it: the screen's right edge on the line of sight to the block's centre.
  TriangleMesh half;
  half.append(make_box_mesh({1.0, 0.01, 1.0}),
              pose_from_xyz_rpy(middle - Eigen::Vector3d(0.5, 0, 0), {0, 0, 0}));
  const double hidden = hidden_behind(half);
  EXPECT_GT(hidden, 0.25);
  EXPECT_LT(hidden, 0.75);
}

TEST(RandomViewpoint, KeepsToItsRangesAndLooksAtTheTarget) {
  const Eigen::Vector3d target(0.3, 0.2, 0.8), reference(0.3, -1.0, 1.3);
  const ViewpointRange range;
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    const Eigen::Isometry3d T = random_viewpoint(target, reference, seed, range);
    const Eigen::Vector3d eye = T.translation();
    const double distance = (eye - target).norm();
    EXPECT_GE(distance, range.min_range - 1e-9);
    EXPECT_LE(distance, range.max_range + 1e-9);
    EXPECT_GE(eye.z(), std::min(range.min_height, target.z()) - 1e-9);
    EXPECT_LE(eye.z(), range.max_height + 1e-9);
    Eigen::Vector3d horizontal = eye - target, towards_reference = reference - target;
    horizontal.z() = towards_reference.z() = 0.0;
    const double azimuth = std::acos(horizontal.normalized().dot(towards_reference.normalized()));
    EXPECT_LE(azimuth, range.max_azimuth + 1e-9);
    EXPECT_LT((T * Eigen::Vector3d(0, 0, distance) - target).norm(), 1e-9);  // the optical axis
    EXPECT_GT((T.linear() * Eigen::Vector3d(0, -1, 0)).z(), 0.0);            // the image's up is up
    EXPECT_TRUE(T.isApprox(random_viewpoint(target, reference, seed, range), 0.0));
  }
}

}  // namespace
}  // namespace lmk
