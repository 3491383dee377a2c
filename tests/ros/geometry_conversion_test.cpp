// SPDX-License-Identifier: BSD-3-Clause
// Poses, boxes and matches as ROS messages.
#include "lmk/ros/geometry_conversion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "lmk/geometry/pose.h"
#include "lmk/ros/box_capture_markers.h"
#include "tests/support/test_support.h"

namespace lmk::ros1 {
namespace {

TEST(GeometryConversion, PosesRoundTrip) {
  const Eigen::Isometry3d T =
      pose_from_xyz_rpy(Eigen::Vector3d(0.4, -0.2, 0.9), Eigen::Vector3d(0.3, -1.1, 2.5));
  const Eigen::Isometry3d back = from_ros(to_ros(T), "pose");
  EXPECT_TRUE(back.isApprox(T, 1e-12));
}

TEST(GeometryConversion, PosesFromTheWireAreChecked) {
  geometry_msgs::Pose pose;  // all zero: not a rotation
  EXPECT_NE(test::error_of([&] {
              from_ros(pose, "box_pose");
            }).find("box_pose.orientation: is not a unit quaternion"),
            std::string::npos);
  pose.orientation.w = 1.0;
  pose.position.x = std::numeric_limits<double>::infinity();
  EXPECT_NE(test::error_of([&] { from_ros(pose, "box_pose"); }).find("non-finite"),
            std::string::npos);
}

TEST(GeometryConversion, MatchesCarryPoseBoxErrorAndTerms) {
  Match match;
  match.T_scene_capture = pose_from_xyz_rpy(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0, 0, 0.5));
  match.box = Box(match.T_scene_capture, Eigen::Vector3d(0.1, 0.2, 0.3));
  match.terms.scene_to_landmark_sum = 0.5;
  match.terms.scene_to_landmark_count = 100;
  match.terms.finish();
  match.error = match.terms.error;
  const lmk_msgs::LandmarkMatch msg = to_ros(match, "milk", 2);
  EXPECT_EQ(msg.landmark, "milk");
  EXPECT_EQ(msg.rank, 2u);
  EXPECT_DOUBLE_EQ(msg.error, 0.005);
  EXPECT_EQ(msg.terms.scene_to_landmark_count, 100u);
  EXPECT_TRUE(std::isnan(msg.terms.coverage));
  EXPECT_DOUBLE_EQ(msg.box_size.z, 0.3);
  EXPECT_TRUE(from_ros(msg.pose, "pose").isApprox(match.T_scene_capture, 1e-12));
}

TEST(GeometryConversion, MatchMarkersClearTheLastSearchThenDrawEachMatch) {
  Match match;
  match.box = Box(Eigen::Isometry3d::Identity(), Eigen::Vector3d(0.1, 0.1, 0.2));
  match.error = 0.0042;
  const std::vector<lmk_msgs::LandmarkMatch> matches = {to_ros(match, "cup", 1),
                                                        to_ros(match, "cup", 2)};
  const visualization_msgs::MarkerArray array =
      match_markers(matches, "base_link", find_error_metric("visibility"));
  ASSERT_EQ(array.markers.size(), 5u);  // DELETEALL, then a box and a label per match
  EXPECT_EQ(array.markers[0].action, visualization_msgs::Marker::DELETEALL);
  EXPECT_EQ(array.markers[1].type, visualization_msgs::Marker::CUBE);
  EXPECT_EQ(array.markers[1].header.frame_id, "base_link");
  EXPECT_NE(array.markers[1].color.g, array.markers[3].color.g);  // the best one stands out
  EXPECT_EQ(array.markers[2].text, "cup #1  4.2 mm");
  EXPECT_NE(array.markers[1].id, array.markers[3].id);
  // The sensor metric's errors are in sigma, and its labels say so.
  match.error = 1.3;
  EXPECT_EQ(match_markers({to_ros(match, "cup", 1)}, "base_link", find_error_metric("sensor"))
                .markers[2]
                .text,
            "cup #1  1.30 sigma");
}

TEST(GeometryConversion, AMatchCarriesItsConfidenceAndCompetitor) {
  Match match;
  match.box = Box(Eigen::Isometry3d::Identity(), Eigen::Vector3d(0.1, 0.1, 0.2));
  match.confidence.probability = 0.3;
  match.confidence.competitor.kind = Competitor::Kind::slide;
  match.confidence.competitor.distance = 0.08;
  match.confidence.competitor.box =
      Box(pose_from_xyz_rpy({0.08, 0, 0}, {0, 0, 0}), Eigen::Vector3d(0.1, 0.1, 0.2));
  match.confidence.doubt = "a pose 8 cm along the box's x fits within the noise";
  const lmk_msgs::LandmarkMatch msg = to_ros(match, "cup", 1);
  EXPECT_DOUBLE_EQ(msg.confidence.probability, 0.3);
  EXPECT_EQ(msg.confidence.competitor_kind, "slide");
  EXPECT_DOUBLE_EQ(msg.confidence.competitor_box_pose.position.x, 0.08);
  EXPECT_EQ(msg.confidence.doubt, match.confidence.doubt);
}

TEST(GeometryConversion, MatchMarkersAreColouredByConfidence) {
  Match sure, doubtful, uncalibrated;
  for (Match* m : {&sure, &doubtful, &uncalibrated}) {
    m->box = Box(Eigen::Isometry3d::Identity(), Eigen::Vector3d(0.1, 0.1, 0.2));
    m->error = 0.003;
  }
  sure.confidence.probability = 0.95;
  doubtful.confidence.probability = 0.1;
  const visualization_msgs::MarkerArray array = match_markers(
      {to_ros(sure, "cup", 1), to_ros(doubtful, "cup", 2), to_ros(uncalibrated, "cup", 3)},
      "base_link", find_error_metric("visibility"));
  ASSERT_EQ(array.markers.size(), 7u);
  const std_msgs::ColorRGBA& green = array.markers[1].color;
  const std_msgs::ColorRGBA& red = array.markers[3].color;
  EXPECT_GT(green.g, green.r);
  EXPECT_GT(red.r, red.g);
  EXPECT_EQ(array.markers[2].text, "cup #1  3.0 mm  confidence 0.95");
  EXPECT_EQ(array.markers[6].text, "cup #3  3.0 mm");  // no calibration: no confidence shown
}

TEST(BoxCaptureMarkers, DraggingAFaceResizesTheBoxAndKeepsTheOppositeFace) {
  const Box box(pose_from_xyz_rpy(Eigen::Vector3d(1, 0, 0.5), Eigen::Vector3d(0, 0, M_PI / 2)),
                Eigen::Vector3d(0.2, 0.4, 0.6));
  // The +x face dragged from 0.1 to 0.3 from the centre: 0.4 long, centre 0.1 along the box's x.
  const Box wider = move_box_face(box, 0, 1, 0.3);
  EXPECT_NEAR(wider.size.x(), 0.4, 1e-12);
  EXPECT_TRUE(wider.pose.linear().isApprox(box.pose.linear()));
  EXPECT_TRUE(wider.center().isApprox(box.pose * Eigen::Vector3d(0.1, 0, 0), 1e-12));
  // The -z face dragged past the +z face stops 1 cm short of it.
  const Box flat = move_box_face(box, 2, -1, 0.5);
  EXPECT_NEAR(flat.size.z(), 0.01, 1e-12);
  EXPECT_TRUE((flat.pose * Eigen::Vector3d(0, 0, 0.005))
                  .isApprox(box.pose * Eigen::Vector3d(0, 0, 0.3), 1e-12));
  EXPECT_NE(test::error_of([&] { move_box_face(box, 3, 1, 0.0); }).find("bad face"),
            std::string::npos);
}

}  // namespace
}  // namespace lmk::ros1
