// SPDX-License-Identifier: BSD-3-Clause
// What the head cannot see because it stands too near (pbd/collision_scene.h, min_range and
// blind_width): a board nearer than the sensor's minimum range leaves a hole in the image, and the
// space in front of the sensor's range along its rays blocks the arm; a narrow strip of dropouts
// and a projector's shadow do not; the padding holds beside the hole as well as in it.

#include <gtest/gtest.h>

#include <limits>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/solid.h"
#include "lmk/pbd/collision_scene.h"
#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/mesh.h"

namespace lmk {
namespace {

// A noise-free Kinect at the origin looking along +z, whatever stands in `near` (boxes: centre,
// size) before a wall at 2 m. The reach holds the view's first 2.2 m, the robot's column none of
// it.
PointCloud frame_with(const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& near) {
  DepthSensorSettings sensor;
  sensor.noise = false;
  TriangleMesh scene;
  scene.append(make_box_mesh({20.0, 20.0, 0.01}), pose_from_xyz_rpy({0, 0, 2.005}, {0, 0, 0}));
  for (const auto& [centre, size] : near)
    scene.append(make_box_mesh(size), pose_from_xyz_rpy(centre, {0, 0, 0}));
  return render_depth(scene, Eigen::Isometry3d::Identity(), sensor);
}

CollisionSceneSettings everywhere() {
  CollisionSceneSettings s;
  s.reach = Box(pose_from_xyz_rpy({0, 0, 1.0}, {0, 0, 0}), Eigen::Vector3d(1.2, 1.2, 2.4));
  s.own_column = Box(pose_from_xyz_rpy({50, 50, 50}, {0, 0, 0}), Eigen::Vector3d(1, 1, 1));
  return s;
}

// The distance of a 1 cm ball at `at` to the scene, looked for up to 10 cm away.
double ball_distance(const CollisionScene& scene, const Eigen::Vector3d& at) {
  const Solid ball = Solid::sphere(0.01);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = at;
  return scene.distance(ball, T, ball.surface_points(0.005), 0.1).distance;
}

TEST(BlindZone, ABoardNearerThanTheSensorsRangeBlocksTheSpaceBeforeIt) {
  // A board 20 cm wide at 0.3 m: nearer than the Kinect's 0.5 m, so the image has a hole there.
  const PointCloud frame = frame_with({{{0.0, 0.0, 0.3}, {0.2, 0.2, 0.01}}});
  const CollisionScene scene(frame, everywhere());
  // On the board's rays, between it and the sensor's range: unknown, so occupied.
  EXPECT_LT(ball_distance(scene, {0.0, 0.0, 0.4}), 0.0);
  EXPECT_LT(ball_distance(scene, {0.0, 0.0, 0.2}), 0.0);
  // Off its rays, seen through to the wall: free.
  EXPECT_GT(ball_distance(scene, {0.3, 0.0, 0.4}), 0.05);
  // Without a minimum range, a ray that returned nothing is free all along, as before.
  CollisionSceneSettings no_range = everywhere();
  no_range.min_range = 0.0;
  EXPECT_GT(ball_distance(CollisionScene(frame, no_range), {0.0, 0.0, 0.4}), 0.05);
}

TEST(BlindZone, TheDistanceBesideTheHoleIsMeasuredAcrossItsEdge) {
  const PointCloud frame = frame_with({{{0.0, 0.0, 0.3}, {0.2, 0.2, 0.01}}});
  const CollisionScene scene(frame, everywhere());
  // At 0.4 m the board's rays reach 0.4 / 0.3 x 0.1 = 13.3 cm from the axis. A ball whose centre
  // is 2 cm beyond that comes within 1 cm of them: near, though its own rays saw the wall.
  const double beside = ball_distance(scene, {0.1533, 0.0, 0.4});
  EXPECT_GT(beside, 0.0);
  EXPECT_LT(beside, 0.015);
}

TEST(BlindZone, ANarrowHoleIsADropoutNotSomethingStandingThere) {
  // A pole 1.5 cm wide at 0.3 m: a hole narrower than blind_width (3 cm at 0.5 m: 2.5 cm
  // at 0.3 m... 1.5 cm is 26 pixels, under the 31 of the opening).
  const PointCloud frame = frame_with({{{0.0, 0.0, 0.3}, {0.015, 0.4, 0.01}}});
  EXPECT_GT(ball_distance(CollisionScene(frame, everywhere()), {0.0, 0.0, 0.4}), 0.0);
  // A narrower blind_width holds it.
  CollisionSceneSettings fine = everywhere();
  fine.blind_width = 0.005;
  EXPECT_LT(ball_distance(CollisionScene(frame, fine), {0.0, 0.0, 0.4}), 0.0);
}

TEST(BlindZone, AProjectorsShadowIsNoHole) {
  // A box at 0.7 m, in the sensor's range, casts the projector's shadow on the wall beside it:
  // a strip without return (at 0.7 m, 0.075 x 580 x (1/0.7 - 1/2) = 40 pixels, wider than the
  // opening's 31). Its rays are lit up to the box's depth, so their first half metre is free.
  const PointCloud frame = frame_with({{{0.0, 0.0, 0.7}, {0.2, 0.2, 0.01}}});
  std::size_t none = 0;
  for (const Eigen::Vector3f& p : frame.points) none += is_finite(p) ? 0 : 1;
  ASSERT_GT(none, 1000u);
  // Left of the box as the camera sees it, where the shadow falls, at 0.4 m.
  const double shadow_x = -0.105 * 0.4 / 0.7 - 0.01;
  EXPECT_GT(ball_distance(CollisionScene(frame, everywhere()), {shadow_x, 0.0, 0.4}), 0.0);
}

TEST(BlindZone, BadSettingsAreRefused) {
  const PointCloud frame = frame_with({});
  CollisionSceneSettings s = everywhere();
  s.min_range = -0.1;
  EXPECT_THROW(CollisionScene scene(frame, s), Error);
  s = everywhere();
  s.blind_width = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(CollisionScene scene(frame, s), Error);
}

}  // namespace
}  // namespace lmk
