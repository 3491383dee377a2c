// SPDX-License-Identifier: BSD-3-Clause
#include <gtest/gtest.h>

#include <set>

#include "lmk/geometry/error.h"
#include "lmk/geometry/filters.h"
#include "lmk/geometry/pose.h"
#include "lmk/landmark/landmark.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

const Box kBox(pose_from_xyz_rpy({0.1, 0.0, 0.0}, {0.2, 0.0, 0.5}), {0.3, 0.2, 0.2});

TEST(Capture, KeepsTheBoxPointsDownsampledWithTheSensor) {
  PointCloud scene = test::random_cloud(200000, 1, 0.5f);
  scene.T_cloud_sensor.translation() << 0.0, 0.0, -2.0;
  const Landmark l = capture(scene, kBox, "block");
  EXPECT_EQ(l.name, "block");
  EXPECT_EQ(l.format_version, kLandmarkFormatVersion);
  EXPECT_EQ(l.sensor_origin, Eigen::Vector3d(0, 0, -2));
  EXPECT_TRUE(l.box.pose.isApprox(kBox.pose));
  // At most one point per 5 mm voxel, and every point is the centroid of box points: inside.
  std::set<std::array<long long, 3>> voxels;
  for (const auto& p : l.points.points) {
    EXPECT_TRUE(kBox.contains(p));
    voxels.insert({static_cast<long long>(std::floor(p.x() / 0.005)),
                   static_cast<long long>(std::floor(p.y() / 0.005)),
                   static_cast<long long>(std::floor(p.z() / 0.005))});
  }
  EXPECT_EQ(voxels.size(), l.points.size());
  EXPECT_LT(l.points.size(), crop(scene, kBox).size());
  EXPECT_NO_THROW(l.validate("test"));
  // A sensor origin no depth camera could have had (a forged 1e300, issue #61) is refused.
  Landmark far = l;
  far.sensor_origin = Eigen::Vector3d(1e300, 0, 0);
  EXPECT_THROW(far.validate("test"), Error);
  far.sensor_origin = l.box.center() + Eigen::Vector3d(0, 0, 150);
  EXPECT_THROW(far.validate("test"), Error);
}

void expect_capture_error(const PointCloud& scene, const Box& box, const std::string& problem,
                          const CaptureSettings& settings = {}, const std::string& name = "x") {
  try {
    capture(scene, box, name, settings);
    ADD_FAILURE() << "capture did not fail; expected: " << problem;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
  }
}

// CaptureSettings's description is its validation: each field's limits, named with its flag, and
// the band against the leaf.
TEST(Capture, SettingsAreCheckedByTheirDescription) {
  const auto error_with = [](auto change) {
    CaptureSettings s;
    change(s);
    return test::error_of([&] { check_capture_settings(s, "capture"); });
  };
  EXPECT_NO_THROW(check_capture_settings(CaptureSettings(), "capture"));
  EXPECT_NE(error_with([](CaptureSettings& s) {
              s.projector_baseline = -0.1;
            }).find("capture: projector_baseline (--projector-baseline): -0.1 must be finite"),
            std::string::npos);
  EXPECT_NE(error_with([](CaptureSettings& s) { s.veil_angle = 2.0; }).find("veil_angle"),
            std::string::npos);
  EXPECT_NE(error_with([](CaptureSettings& s) {
              s.up = Eigen::Vector3d::Zero();
            }).find("up (--up): must be a finite non-zero vector"),
            std::string::npos);
  EXPECT_NE(error_with([](CaptureSettings& s) {
              s.distance_band = 0.004;
            }).find("must be at least the leaf size"),
            std::string::npos);
  EXPECT_NE(error_with([](CaptureSettings& s) {
              s.empty_space_margin = NAN;
            }).find("empty_space_margin (--empty-space-margin): nan"),
            std::string::npos);
}

TEST(Capture, RejectsBadBoxesAndTooFewPoints) {
  const PointCloud scene = test::random_cloud(50000, 2, 0.5f);
  Box box = kBox;
  box.size.x() = 0.0;
  expect_capture_error(scene, box, "sides must be positive and finite");
  box.size.x() = std::nan("");
  expect_capture_error(scene, box, "sides must be positive and finite");
  box = kBox;
  box.pose.translation().x() = std::nan("");
  expect_capture_error(scene, box, "box pose");
  box = kBox;
  box.size.z() = 4.0;
  expect_capture_error(scene, box, "over the 3");
  box = kBox;
  box.pose.translation() << 5, 5, 5;
  expect_capture_error(scene, box, "no scene point inside the box");
  box = Box(Eigen::Isometry3d::Identity(), {0.06, 0.06, 0.06});  // about 11 points
  expect_capture_error(scene, box, "fewer than the minimum of 30");
  expect_capture_error(scene, kBox, "needs a name", {}, "");
}

}  // namespace
}  // namespace lmk
