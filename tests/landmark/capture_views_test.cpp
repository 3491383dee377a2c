// SPDX-License-Identifier: BSD-3-Clause
// Landmarks from several views (landmark/capture_views.h): fusion of points and free space, the
// one-view case, the views in the .lmk file, registration of the views, and searching.

#include "lmk/landmark/capture_views.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lmk/geometry/error.h"
#include "lmk/geometry/kdtree.h"
#include "lmk/geometry/pose.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/search/confidence/view_determinacy.h"
#include "lmk/search/find_landmark.h"
#include "lmk/search/metrics/grid_metrics.h"
#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/mesh.h"
#include "tests/landmark/l_shape_scene.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

using namespace test_scenes;
// The second view: from the table's right, where the L-shape's arm end and right side show.
Eigen::Isometry3d side_camera() {
  return camera_look_at({0.8, 0.1, kTable + 0.7}, {0, 0, kTable}, Eigen::Vector3d::UnitZ());
}

// A third view, for searching: from the left and behind the capture camera.
Eigen::Isometry3d third_camera() {
  return camera_look_at({-0.6, -0.7, kTable + 0.8}, {0, 0, kTable}, Eigen::Vector3d::UnitZ());
}

class CaptureViews : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    front_ = new PointCloud(render_scene(kCopies, true));
    side_ = new PointCloud(render_scene(kCopies, true, {}, side_camera()));
  }
  static void TearDownTestSuite() {
    delete front_;
    delete side_;
  }
  // Both renders are in the world frame: the views' poses are the identity.
  static Landmark fused() {
    return capture_views(
        {{front_, Eigen::Isometry3d::Identity()}, {side_, Eigen::Isometry3d::Identity()}},
        box_at(kCopies[1]), "L");
  }
  static PointCloud* front_;
  static PointCloud* side_;
};
PointCloud* CaptureViews::front_ = nullptr;
PointCloud* CaptureViews::side_ = nullptr;

TEST_F(CaptureViews, OneViewIsCaptureBitForBit) {
  const Landmark one = capture(*front_, box_at(kCopies[1]), "L");
  const Landmark views =
      capture_views({{front_, Eigen::Isometry3d::Identity()}}, box_at(kCopies[1]), "L");
  EXPECT_FALSE(views.multi_view());
  EXPECT_TRUE(views.point_views.empty());
  ASSERT_EQ(views.points.size(), one.points.size());
  for (std::size_t i = 0; i < one.points.size(); ++i) {
    ASSERT_EQ(views.points.points[i], one.points.points[i]) << i;
  }
  EXPECT_EQ(views.empty_space.centres(), one.empty_space.centres());
}

TEST_F(CaptureViews, FusedPointsAreTheFirstViewsAndTheSurfacesOnlyTheOtherSaw) {
  const Box box = box_at(kCopies[1]);
  const Landmark front = capture(*front_, box, "L");
  const Landmark side = capture(*side_, box, "L");
  const Landmark both = fused();
  ASSERT_TRUE(both.multi_view());
  ASSERT_EQ(both.view_count(), 2u);
  EXPECT_EQ(both.view_origins[0], front_->sensor_origin());
  EXPECT_EQ(both.view_origins[1], side_->sensor_origin());
  // The first view's points, bit for bit and in order, then what only the side view measured.
  ASSERT_GT(both.points.size(), front.points.size());
  for (std::size_t i = 0; i < front.points.size(); ++i) {
    ASSERT_EQ(both.points.points[i], front.points.points[i]) << i;
    EXPECT_TRUE(both.point_views[i] == 1u || both.point_views[i] == 3u);
  }
  // Two points of one surface merge within two leaves (these renders are noiseless, and 3 sigma
  // of a Kinect at a metre is less).
  const double merge = 2.0 * both.settings.leaf_size;
  const KdTree front_points(front.points), fused_points(both.points);
  std::size_t shared = 0;
  for (std::size_t i = front.points.size(); i < both.points.size(); ++i) {
    EXPECT_EQ(both.point_views[i], 2u);
    EXPECT_GT(std::sqrt(front_points.knn(both.points.points[i], 1)[0].squared_distance), merge);
  }
  // Every point of the side view is in the fused surface, its nearest fused point marked as seen
  // by it.
  for (const Eigen::Vector3f& p : side.points.points) {
    const Neighbor n = fused_points.knn(p, 1)[0];
    EXPECT_LE(std::sqrt(n.squared_distance), merge + 1e-6);
    EXPECT_TRUE((both.point_views[n.index] & 2u) != 0u);
    if (both.point_views[n.index] == 3u) ++shared;
  }
  // The side view adds a side the front never saw, and both see the top of the arm.
  EXPECT_GT(both.points.size(), front.points.size() + front.points.size() / 10);
  EXPECT_GT(shared, 0u);
  EXPECT_NO_THROW(both.validate("fused"));
}

TEST_F(CaptureViews, FreeSpaceIsWhatEitherViewSawFreeAwayFromAnyViewsSurface) {
  const Box box = box_at(kCopies[1]);
  const Landmark front = capture(*front_, box, "L");
  const Landmark side = capture(*side_, box, "L");
  const Landmark both = fused();
  const KdTree surface(both.points);
  const double margin = both.settings.empty_space_margin;
  const auto sampler = both.empty_space.sampler();
  // Every voxel one view saw free stays free, unless the other view measured a surface within
  // the margin of it: a measured surface outweighs a ray that passed by.
  for (const Landmark* view : {&front, &side}) {
    std::size_t kept = 0, overruled = 0;
    for (const Eigen::Vector3f& c : view->empty_space.centres()) {
      if (sampler.is_empty(c)) {
        ++kept;
      } else {
        const auto nearest = surface.knn(c, 1);
        ASSERT_FALSE(nearest.empty());
        EXPECT_LT(std::sqrt(nearest[0].squared_distance), margin + 1e-6) << c.transpose();
        ++overruled;
      }
    }
    EXPECT_GT(kept, 9 * overruled);
  }
  // And the union holds space neither view alone could call free (beside what it never saw).
  std::size_t new_free = 0;
  for (const Eigen::Vector3f& c : both.empty_space.centres()) {
    if (!front.empty_space.is_empty(c) && !side.empty_space.is_empty(c)) ++new_free;
  }
  EXPECT_GT(both.empty_space.size(), std::max(front.empty_space.size(), side.empty_space.size()));
  EXPECT_GT(new_free, 0u);
}

TEST_F(CaptureViews, TheFileKeepsTheViews) {
  const test::ScratchDir dir;
  const std::string fused_path = dir.file("fused.lmk");
  const std::string one_path = dir.file("one.lmk");
  const Landmark both = fused();
  save_landmark(fused_path, both);
  const Landmark loaded = load_landmark(fused_path);
  EXPECT_EQ(loaded.view_origins, both.view_origins);
  EXPECT_EQ(loaded.point_views, both.point_views);
  ASSERT_EQ(loaded.points.size(), both.points.size());
  for (std::size_t i = 0; i < both.points.size(); ++i) {
    ASSERT_EQ(loaded.points.points[i], both.points.points[i]);
    // Normals face a view that saw the point: recomputed on load exactly as at capture.
    ASSERT_TRUE(loaded.points.normals[i].isApprox(both.points.normals[i]) ||
                !loaded.points.normals[i].allFinite());
  }
  EXPECT_EQ(landmark_file_version(fused_path), kLandmarkFormatVersion);
  save_landmark(one_path, capture(*front_, box_at(kCopies[1]), "L"));
  EXPECT_FALSE(load_landmark(one_path).multi_view());
  // Export and import carry the views too (each point's views are points.pcd's labels).
  export_landmark(both, dir.file("export"));
  const Landmark imported = import_landmark(dir.file("export"));
  EXPECT_EQ(imported.view_origins, both.view_origins);
  EXPECT_EQ(imported.point_views, both.point_views);
}

TEST_F(CaptureViews, BadViewsAreRefusedByName) {
  const Box box = box_at(kCopies[1]);
  EXPECT_NE(test::error_of([&] { capture_views({}, box, "L"); }).find("1 to 16 views"),
            std::string::npos);
  Eigen::Isometry3d far_away = Eigen::Isometry3d::Identity();
  far_away.translation() << 5.0, 0.0, 0.0;
  EXPECT_NE(test::error_of([&] {
              capture_views({{front_, Eigen::Isometry3d::Identity()}, {side_, far_away}}, box, "L");
            }).find("view 2 has no point inside the box"),
            std::string::npos);
  Eigen::Isometry3d not_rigid = Eigen::Isometry3d::Identity();
  not_rigid.linear() *= 2.0;
  EXPECT_NE(
      test::error_of([&] {
        capture_views({{front_, Eigen::Isometry3d::Identity()}, {side_, not_rigid}}, box, "L");
      }).find("view 2 needs a cloud and a finite pose"),
      std::string::npos);
  Landmark both = fused();
  both.point_views[0] = 4u;  // a third view it does not have
  EXPECT_NE(test::error_of([&] { both.validate("x"); }).find("a view the landmark does not have"),
            std::string::npos);
}

TEST_F(CaptureViews, RegistrationRecoversAViewsOffsetAndRefusesViewsThatDoNotOverlap) {
  const Box box = box_at(kCopies[1]);
  // The side view as if its frame were off by 3 cm and 3 degrees: registered from the identity,
  // it comes back onto the first view.
  const Eigen::Isometry3d offset = pose_from_xyz_rpy({0.03, -0.02, 0.01}, {0.0, 0.0, 0.05});
  const PointCloud moved = side_->transformed(offset);
  const ViewRegistration r = register_view(*front_, moved, Eigen::Isometry3d::Identity(), box, 2);
  const Eigen::Isometry3d error = r.T_first_view * offset;  // identity when exact
  EXPECT_LT((error * box.center() - box.center()).norm(), 0.003);
  EXPECT_LT(rotation_angle_between(error.linear(), Eigen::Matrix3d::Identity()), 0.005);
  EXPECT_GT(r.overlap, 0.5);
  EXPECT_LT(r.residual, 0.005);
  EXPECT_GT(r.moved, 0.02);
  // The same view 2 m away overlaps nothing of the first.
  const PointCloud elsewhere = side_->transformed(pose_from_xyz_rpy({2.0, 0, 0}, {0, 0, 0}));
  EXPECT_NE(test::error_of([&] {
              register_view(*front_, elsewhere, Eigen::Isometry3d::Identity(), box, 2);
            }).find("view 2: does not overlap the first view enough"),
            std::string::npos);
}

TEST_F(CaptureViews, AFusedLandmarkIsFoundFromAThirdViewAndShowsOnlyItsFacingSide) {
  const Landmark both = fused();
  const PointCloud third = render_scene(kCopies, true, {}, third_camera());
  const FindResult r = find_landmark(third, both, FindSettings());
  std::vector<int> found(kCopies.size(), 0);
  for (const Match& m : r.matches) {
    for (std::size_t c = 0; c < kCopies.size(); ++c) {
      if ((m.box.center() - box_at(kCopies[c]).center()).norm() < 0.0254 &&
          rotation_angle_between(m.box.pose.linear(), Eigen::Matrix3d::Identity()) < 0.2618) {
        ++found[c];
      }
    }
  }
  EXPECT_EQ(found, std::vector<int>(kCopies.size(), 1));
  // At its true place in the front view, the points only the side view saw are turned away.
  const FindResult self = find_landmark(*front_, both, FindSettings());
  ASSERT_FALSE(self.matches.empty());
  EXPECT_GT(self.matches.front().terms.support->unseen_points, 0u);
}

}  // namespace
}  // namespace lmk

namespace lmk {
namespace {

// A 20 cm square of points 5 mm apart at `depth` in front of a sensor at the origin looking along
// +z, turned by `tilt` about the x axis, with normals facing the sensor.
PointCloud square(float depth, float tilt) {
  PointCloud out;
  const Eigen::Matrix3f turn = Eigen::AngleAxisf(tilt, Eigen::Vector3f::UnitX()).toRotationMatrix();
  for (int i = -20; i <= 20; ++i) {
    for (int j = -20; j <= 20; ++j) {
      out.points.push_back(Eigen::Vector3f(0, 0, depth) +
                           turn * Eigen::Vector3f(0.005f * i, 0.005f * j, 0));
      out.normals.push_back(turn * -Eigen::Vector3f::UnitZ());
    }
  }
  out.set_unorganized();
  return out;
}

TEST(SelfHidden, TheBackOfTwoLayersIsHiddenAndAnObliqueSurfaceHidesNothingOfItself) {
  const Eigen::Isometry3f identity = Eigen::Isometry3f::Identity();
  const Eigen::Vector3f sensor = Eigen::Vector3f::Zero(), centre(0, 0, 1.05f);
  PointCloud layers = square(1.0f, 0.0f);
  const PointCloud back = square(1.1f, 0.0f);
  layers.points.insert(layers.points.end(), back.points.begin(), back.points.end());
  layers.normals.insert(layers.normals.end(), back.normals.begin(), back.normals.end());
  layers.set_unorganized();
  const std::vector<char> hidden = self_hidden(layers, identity, sensor, centre, 0.01);
  const std::size_t n = back.size();
  // The back square's middle lies behind the front's (its rim, seen past the front's edge at a
  // range 10% farther, may show).
  std::size_t back_hidden = 0;
  for (std::size_t j = 0; j < n; ++j) {
    EXPECT_FALSE(hidden[j]) << "a front point hidden";
    back_hidden += hidden[n + j] ? 1 : 0;
  }
  EXPECT_GT(back_hidden, n * 8 / 10);
  // One plane seen 70 degrees from its normal recedes steeply across the image, hiding nothing.
  const std::vector<char> oblique =
      self_hidden(square(1.0f, 1.22f), identity, sensor, {0, 0, 1.0f}, 0.01);
  EXPECT_EQ(std::count(oblique.begin(), oblique.end(), 1), 0);
}

}  // namespace
}  // namespace lmk

namespace lmk {
namespace {

// A mug: a cylinder with a handle on its -y side, standing at the origin.
TriangleMesh mug() {
  TriangleMesh mesh;
  mesh.append(make_cylinder_mesh(0.04, 0.1, 64), pose_from_xyz_rpy({0, 0, 0.05}, {0, 0, 0}));
  mesh.append(make_box_mesh({0.015, 0.025, 0.06}), pose_from_xyz_rpy({0, -0.05, 0.05}, {0, 0, 0}));
  return mesh;
}

PointCloud render_mug(const Eigen::Vector3d& eye) {
  DepthSensorSettings sensor;
  sensor.noise = false;
  return render_depth(mug(), camera_look_at(eye, {0, 0, 0.05}, Eigen::Vector3d::UnitZ()), sensor);
}

// From where its handle is hidden, a fused mug shows a plain cylinder, free to turn about its axis,
// which its demonstration view, handle and all, was not: that match cannot fix the pose. Seen from
// the handle's side it can.
TEST(ViewDeterminacy, AMugSeenFromBehindItsHandleCannotFixItsTurn) {
  const PointCloud front = render_mug({0, -0.7, 0.35});
  const PointCloud side = render_mug({0.5, -0.5, 0.35});
  const Landmark fused = capture_views(
      {{&front, Eigen::Isometry3d::Identity()}, {&side, Eigen::Isometry3d::Identity()}},
      Box(pose_from_xyz_rpy({0, -0.01, 0.055}, {0, 0, 0}), {0.11, 0.13, 0.12}), "mug");
  const Eigen::Isometry3d here = Eigen::Isometry3d::Identity();
  EXPECT_FALSE(
      detail::shows_too_little_to_fix(SceneIndex(render_mug({0.1, -0.7, 0.35})), fused, here));
  EXPECT_TRUE(
      detail::shows_too_little_to_fix(SceneIndex(render_mug({0.0, 0.7, 0.35})), fused, here));
  // A landmark of one view is never judged so: it is searched with every point.
  EXPECT_FALSE(detail::shows_too_little_to_fix(SceneIndex(render_mug({0.0, 0.7, 0.35})),
                                               capture(front, fused.box, "mug"), here));
}

}  // namespace
}  // namespace lmk
