// SPDX-License-Identifier: BSD-3-Clause
// The range image behind projective visibility: an organised cloud's intrinsics are recovered from
// its pixels, a cloud whose pose does not explain its pixels has no image, and an unorganised
// cloud keeps the nearest point of each pixel.

#include "lmk/geometry/range_image.h"

#include <gtest/gtest.h>

#include "lmk/geometry/pose.h"

namespace lmk {
namespace {

// A 64 x 48 view (fx 50, fy 52, centre 31.2, 23.9) of a slanted plane, seen from T_world_sensor.
PointCloud view(const Eigen::Isometry3d& T_world_sensor) {
  PointCloud cloud;
  cloud.width = 64;
  cloud.height = 48;
  for (int v = 0; v < 48; ++v) {
    for (int u = 0; u < 64; ++u) {
      const double x = (u - 31.2) / 50.0, y = (v - 23.9) / 52.0, z = 1.5 + 0.4 * x;
      cloud.points.push_back((T_world_sensor * Eigen::Vector3d(x * z, y * z, z)).cast<float>());
    }
  }
  cloud.T_cloud_sensor = T_world_sensor;
  return cloud;
}

TEST(RangeImage, AnOrganisedCloudIsItsOwnImage) {
  const Eigen::Isometry3d T = pose_from_xyz_rpy({0.3, -1.0, 1.2}, {-2.0, 0.1, 0.4});
  const auto image = RangeImage::from_cloud(view(T));
  ASSERT_TRUE(image.has_value());
  EXPECT_TRUE(image->organised());
  EXPECT_NEAR(image->intrinsics().fx, 50.0, 1e-3);
  EXPECT_NEAR(image->intrinsics().fy, 52.0, 1e-3);
  EXPECT_NEAR(image->intrinsics().cx, 31.2, 1e-3);
  EXPECT_NEAR(image->intrinsics().cy, 23.9, 1e-3);
  // A point 10 cm in front of the plane along a pixel's ray: the image measured 10 cm further.
  const Eigen::Vector3d on_plane = T.inverse() * view(T).points[20 * 64 + 10].cast<double>();
  const Eigen::Vector3f nearer = (T * (0.9 * on_plane)).cast<float>();
  const RangeImage::Look look = image->look(nearer);
  ASSERT_TRUE(look.in_view);
  EXPECT_NEAR(look.measured - look.depth, 0.1 * on_plane.z(), 1e-4);
  // Behind the sensor, or outside the image: not in view.
  EXPECT_FALSE(image->look((T * Eigen::Vector3d(0, 0, -1)).cast<float>()).in_view);
  EXPECT_FALSE(image->look((T * Eigen::Vector3d(5, 0, 1)).cast<float>()).in_view);
}

TEST(RangeImage, ACloudItsPoseDoesNotExplainHasNoImage) {
  PointCloud moved = view(Eigen::Isometry3d::Identity());
  moved.T_cloud_sensor = pose_from_xyz_rpy({0.5, 0.2, 0.0}, {0.0, 0.3, 0.0});
  EXPECT_FALSE(RangeImage::from_cloud(moved).has_value());
}

TEST(RangeImage, AnOrganisedCloudWithoutColumnsHasNoImage) {
  PointCloud broken = view(Eigen::Isometry3d::Identity());
  broken.width = 0;  // rows of nothing: no pixel to fit intrinsics to
  EXPECT_FALSE(RangeImage::from_cloud(broken).has_value());
}

// A tracker's stream: the intrinsics fitted to one frame are kept for the next from the same
// camera, the same image as a fit of its own gives; intrinsics that do not fit, or of another
// image size, are fitted again.
TEST(RangeImage, KnownIntrinsicsAreKeptWhereTheyFitAndFittedAgainWhereNot) {
  const auto first = RangeImage::from_cloud(view(Eigen::Isometry3d::Identity()));
  ASSERT_TRUE(first.has_value());
  const PointCloud next = view(pose_from_xyz_rpy({0.1, 0.0, 0.05}, {0.0, 0.05, 0.1}));
  const auto fitted = RangeImage::from_cloud(next);
  const auto kept = RangeImage::from_cloud(next, {}, kMaxIntrinsicsFitRms, &first->intrinsics());
  ASSERT_TRUE(fitted.has_value() && kept.has_value());
  EXPECT_EQ(kept->intrinsics().fx, first->intrinsics().fx);  // taken, not fitted
  // Float points: two frames' fits agree to a few millionths of a pixel.
  EXPECT_NEAR(kept->intrinsics().fx, fitted->intrinsics().fx, 1e-4);
  EXPECT_EQ(kept->depths(), fitted->depths());

  PinholeIntrinsics wrong = first->intrinsics();
  wrong.fx *= 1.2;  // 20% off: pixels several columns from where it projects them
  const auto refitted = RangeImage::from_cloud(next, {}, kMaxIntrinsicsFitRms, &wrong);
  ASSERT_TRUE(refitted.has_value());
  EXPECT_EQ(refitted->intrinsics().fx, fitted->intrinsics().fx);
  EXPECT_EQ(refitted->depths(), fitted->depths());

  PinholeIntrinsics other_size = first->intrinsics();
  other_size.width = 128;
  const auto resized = RangeImage::from_cloud(next, {}, kMaxIntrinsicsFitRms, &other_size);
  ASSERT_TRUE(resized.has_value());
  EXPECT_EQ(resized->intrinsics().width, 64);
  EXPECT_EQ(resized->intrinsics().fx, fitted->intrinsics().fx);

  // A cloud no pinhole view explains has no image, whatever intrinsics are offered.
  PointCloud moved = next;
  moved.T_cloud_sensor = pose_from_xyz_rpy({0.5, 0.2, 0.0}, {0.0, 0.3, 0.0});
  EXPECT_FALSE(RangeImage::from_cloud(moved, {}, kMaxIntrinsicsFitRms, &first->intrinsics()));
}

TEST(RangeImage, AnUnorganisedCloudKeepsTheNearestPointOfEachPixel) {
  PinholeIntrinsics k;
  PointCloud cloud(std::vector<Eigen::Vector3f>{{0, 0, 2.0f}, {0, 0, 1.0f}, {0, 0, 3.0f}});
  const auto image = RangeImage::from_cloud(cloud, k);
  ASSERT_TRUE(image.has_value());
  EXPECT_FALSE(image->organised());
  EXPECT_NEAR(image->look({0, 0, 2.5f}).measured, 1.0, 1e-6);
  EXPECT_TRUE(std::isnan(image->look({0.5f, 0.2f, 2.0f}).measured));  // a pixel without a point
}

}  // namespace
}  // namespace lmk
