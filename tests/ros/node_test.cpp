// SPDX-License-Identifier: BSD-3-Clause
// lmk on ROS 1, end to end against a real rosmaster of the test's own (tests/ros/support):
// lmk_node's services on a fake PR2's camera. The scenes and landmark are the paper's task 3
// ("bowls on a shelf") from lmk's demo tasks (node_fixture.h); pbd_run_on_ros_test.cpp drives
// the fake PR2 with `lmk pbd run --ros`.

#include <actionlib/server/action_server.h>
#include <geometry_msgs/PointStamped.h>
#include <gtest/gtest.h>
#include <lmk_msgs/AddView.h>
#include <lmk_msgs/CaptureLandmark.h>
#include <lmk_msgs/FindLandmark.h>
#include <lmk_msgs/ListLandmarks.h>
#include <lmk_msgs/Track.h>
#include <lmk_msgs/TrackedLandmarks.h>
#include <pr2_controllers_msgs/JointTrajectoryAction.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>
#include <utility>

#include "lmk/demos/demo_tasks.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/range_image.h"
#include "lmk/landmark/box_guess.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/pbd/plan.h"
#include "lmk/pr2/pr2_kinematics.h"
#include "lmk/ros/cloud_conversion.h"
#include "lmk/ros/geometry_conversion.h"
#include "lmk/ros/latest_frame.h"
#include "lmk/ros/ros_robot.h"
#include "tests/ros/node_fixture.h"
#include "tests/ros/support/fake_pr2.h"
#include "tests/ros/support/ros_harness.h"
#include "tests/support/lifecycle_conformance.h"
#include "tests/support/test_support.h"

namespace lmk::test {
namespace {

namespace fs = std::filesystem;

// A capture of the demonstrated box as "rim", the box given in `frame` (T_base_frame is where that
// frame lies in base_link).
lmk_msgs::CaptureLandmark rim_capture(const Landmark& demonstrated, const std::string& frame,
                                      const Eigen::Isometry3d& T_base_frame) {
  lmk_msgs::CaptureLandmark capture;
  capture.request.name = "rim";
  capture.request.box_pose.header.frame_id = frame;
  capture.request.box_pose.pose = ros1::to_ros(T_base_frame.inverse() * demonstrated.box.pose);
  capture.request.box_size = ros1::to_ros(demonstrated.box.size);
  return capture;
}

TEST(LmkNode, CaptureAndFindThroughTheServicesGiveWhatLmkFindGivesOnTheSameFrame) {
  const Landmark demonstrated = load_landmark(demo_data().landmark().string());
  FakePr2 robot(fake_settings("demonstration.pcd"));
  const ScratchDir dir;
  const auto node = start_node(dir, dir.file("landmarks"));

  // The box the demonstration used, given in torso_lift_link: capture takes any TF frame.
  const Pr2Kinematics kinematics(RobotModel::pr2(), 0.0);
  lmk_msgs::CaptureLandmark capture =
      rim_capture(demonstrated, "torso_lift_link", kinematics.T_base_torso());
  capture = call("/lmk_node/capture_landmark", capture);
  ASSERT_TRUE(capture.response.success) << capture.response.message << "\n" << node->log();
  EXPECT_TRUE(capture.response.found_itself);
  EXPECT_TRUE(fs::exists(capture.response.file));
  EXPECT_EQ(capture.response.header.frame_id, "base_link");

  lmk_msgs::ListLandmarks list = call("/lmk_node/list_landmarks", lmk_msgs::ListLandmarks());
  EXPECT_EQ(list.response.names, std::vector<std::string>{"rim"});

  lmk_msgs::FindLandmark find;
  find.request.name = "rim";
  find = call("/lmk_node/find_landmark", find);
  ASSERT_TRUE(find.response.success) << find.response.message;
  ASSERT_FALSE(find.response.matches.empty());

  // lmk find on the same frame and the file the node wrote.
  const ros1::Frame frame = frame_as_the_node_sees_it();
  write_cloud(dir.file("frame.pcd"), frame.scene);
  const auto [code, out] = run_lmk(dir, {"find", dir.file("frame.pcd"), capture.response.file,
                                         "--base-frame", "--json", dir.file("find.json")});
  ASSERT_EQ(code, 0) << out;
  std::ifstream in(dir.file("find.json"));
  const nlohmann::json expected = nlohmann::json::parse(in);
  ASSERT_EQ(expected["matches"].size(), find.response.matches.size());
  for (std::size_t i = 0; i < find.response.matches.size(); ++i) {
    const lmk_msgs::LandmarkMatch& got = find.response.matches[i];
    const nlohmann::json& want = expected["matches"][i];
    EXPECT_DOUBLE_EQ(got.error, want["error"].get<double>()) << i;
    // `lmk find --json` gives each match's box pose as position and quaternion [w, x, y, z].
    const nlohmann::json& p = want["position"];
    const nlohmann::json& q = want["quaternion"];
    EXPECT_NEAR(got.box_pose.position.x, p[0].get<double>(), 1e-9);
    EXPECT_NEAR(got.box_pose.position.y, p[1].get<double>(), 1e-9);
    EXPECT_NEAR(got.box_pose.position.z, p[2].get<double>(), 1e-9);
    EXPECT_NEAR(std::abs(got.box_pose.orientation.w * q[0].get<double>() +
                         got.box_pose.orientation.x * q[1].get<double>() +
                         got.box_pose.orientation.y * q[2].get<double>() +
                         got.box_pose.orientation.z * q[3].get<double>()),
                1.0, 1e-9);
    EXPECT_EQ(got.terms.landmark_to_scene_count,
              want["terms"]["landmark_to_scene_count"].get<std::size_t>());
    EXPECT_EQ(got.rank, i + 1);
  }
}

// ~track (issue #48): a landmark of the directory followed in every frame the camera publishes:
// ~tracked carries its stamped pose, confidence and state, TF gets lmk/NAME, and a stop ends it.
TEST(LmkNode, TrackPublishesEachFramesPosesAndATfFramePerLandmark) {
  const Landmark demonstrated = load_landmark(demo_data().landmark().string());
  FakePr2 robot(fake_settings("demonstration.pcd"));
  const ScratchDir dir;
  const auto node = start_node(dir, dir.file("landmarks"));
  lmk_msgs::CaptureLandmark capture =
      call("/lmk_node/capture_landmark",
           rim_capture(demonstrated, "base_link", Eigen::Isometry3d::Identity()));
  ASSERT_TRUE(capture.response.success) << capture.response.message << "\n" << node->log();

  lmk_msgs::Track bad;
  bad.request.landmarks = {"nothing"};
  bad = call("/lmk_node/track", bad);
  EXPECT_FALSE(bad.response.success);
  EXPECT_NE(bad.response.message.find("nothing"), std::string::npos) << bad.response.message;

  lmk_msgs::Track track;
  track.request.landmarks = {"rim"};
  track = call("/lmk_node/track", track);
  ASSERT_TRUE(track.response.success) << track.response.message;
  EXPECT_EQ(track.response.landmarks, std::vector<std::string>{"rim"});

  // Three frames: the first found by a search, the later ones followed.
  const Eigen::Vector3d truth = demonstrated.box.center();
  std::vector<lmk_msgs::TrackedLandmarks> frames;
  while (frames.size() < 3) {
    const auto msg = ::ros::topic::waitForMessage<lmk_msgs::TrackedLandmarks>("/lmk_node/tracked",
                                                                              ::ros::Duration(30));
    ASSERT_TRUE(msg) << node->log();
    frames.push_back(*msg);
  }
  for (const lmk_msgs::TrackedLandmarks& f : frames) {
    EXPECT_EQ(f.header.frame_id, "base_link");
    ASSERT_EQ(f.landmarks.size(), 1u);
    const lmk_msgs::TrackedLandmark& rim = f.landmarks[0];
    EXPECT_EQ(rim.name, "rim");
    ASSERT_NE(rim.state, "lost") << rim.lost_because;
    const Eigen::Vector3d at(rim.box_pose.position.x, rim.box_pose.position.y,
                             rim.box_pose.position.z);
    EXPECT_LT((at - truth).norm(), 0.01);
    EXPECT_GT(rim.confidence, 0.5);
  }
  EXPECT_EQ(frames.back().landmarks[0].state, "tracking");

  // The landmark as a TF frame, where ~tracked says it is.
  tf2_ros::Buffer tf;
  tf2_ros::TransformListener listener(tf);
  ASSERT_TRUE(tf.canTransform("base_link", "lmk/rim", ::ros::Time(0), ::ros::Duration(10)))
      << node->log();
  const geometry_msgs::TransformStamped T =
      tf.lookupTransform("base_link", "lmk/rim", ::ros::Time(0));
  EXPECT_LT((Eigen::Vector3d(T.transform.translation.x, T.transform.translation.y,
                             T.transform.translation.z) -
             truth)
                .norm(),
            0.01);

  lmk_msgs::Track stop;
  stop.request.stop = true;
  stop = call("/lmk_node/track", stop);
  EXPECT_TRUE(stop.response.success);
  EXPECT_NE(stop.response.message.find("stopped following 'rim'"), std::string::npos)
      << stop.response.message;
}

// ~frames (issue #46): a search fuses the latest frames, as `lmk find A B C` fuses the same frames
// from files. The fake PR2's head does not move, so they are one view with the camera's noise
// rendered once; what this checks is that the node fuses what the CLI fuses.
TEST(LmkNode, WithFramesASearchFusesTheLatestFramesAsLmkFindDoes) {
  FakePr2 robot(fake_settings("demonstration.pcd"));
  const ScratchDir dir;
  fs::create_directories(dir.file("landmarks"));
  fs::copy_file(demo_data().landmark(), dir.file("landmarks/rim.lmk"));
  // A generous timeout: the search waits for the third frame after start-up, no longer.
  const auto node = start_node(dir, dir.file("landmarks"), {"_frames:=3", "_frame_timeout:=60"});
  lmk_msgs::FindLandmark find;
  find.request.name = "rim";
  find = call("/lmk_node/find_landmark", find);
  ASSERT_TRUE(find.response.success) << find.response.message << "\n" << node->log();
  EXPECT_EQ(find.response.message.rfind("3 frames fused; rim: ", 0), 0u) << find.response.message;
  ASSERT_FALSE(find.response.matches.empty());

  const ros1::Frame frame = frame_as_the_node_sees_it();
  write_cloud(dir.file("frame.pcd"), frame.scene);
  const auto [code, out] = run_lmk(
      dir, {"find", dir.file("frame.pcd"), dir.file("frame.pcd"), dir.file("frame.pcd"),
            dir.file("landmarks/rim.lmk"), "--base-frame", "--json", dir.file("find.json")});
  ASSERT_EQ(code, 0) << out;
  std::ifstream in(dir.file("find.json"));
  const nlohmann::json expected = nlohmann::json::parse(in)["matches"];
  ASSERT_EQ(expected.size(), find.response.matches.size());
  // The same places, to the precision of the sensor pose a PCD's VIEWPOINT keeps (single).
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const geometry_msgs::Point& got = find.response.matches[i].box_pose.position;
    EXPECT_NEAR(got.x, expected[i]["position"][0].get<double>(), 1e-4) << i;
    EXPECT_NEAR(got.y, expected[i]["position"][1].get<double>(), 1e-4) << i;
    EXPECT_NEAR(got.z, expected[i]["position"][2].get<double>(), 1e-4) << i;
  }
}

// "Add this view" (issue #35): add_view keeps the latest frame, and a capture with
// use_added_views fuses it after its own frame, as `lmk capture A B` fuses two scenes, point for
// point. The fake PR2's head does not move, so both views are the same frame here; the fusion of
// distinct views through the same place_views is ServeTest.AddingAViewFusesItAsLmkCaptureDoes.
TEST(LmkNode, AddedViewsAreFusedAsLmkCaptureFusesThem) {
  const Landmark demonstrated = load_landmark(demo_data().landmark().string());
  FakePr2 robot(fake_settings("demonstration.pcd"));
  const ScratchDir dir;
  const auto node = start_node(dir, dir.file("landmarks"));

  lmk_msgs::CaptureLandmark capture =
      rim_capture(demonstrated, "base_link", Eigen::Isometry3d::Identity());
  capture.request.force = true;  // the bowl's rim matches the other bowls of this frame
  capture.request.use_added_views = true;
  capture = call("/lmk_node/capture_landmark", capture);
  EXPECT_FALSE(capture.response.success);  // no view added yet: said so
  EXPECT_NE(capture.response.message.find("no view added"), std::string::npos)
      << capture.response.message;

  lmk_msgs::AddView add = call("/lmk_node/add_view", lmk_msgs::AddView());
  ASSERT_TRUE(add.response.success) << add.response.message;
  EXPECT_EQ(add.response.views, 1u);
  capture = call("/lmk_node/capture_landmark", capture);
  ASSERT_TRUE(capture.response.success) << capture.response.message << "\n" << node->log();
  EXPECT_EQ(capture.response.views, 2u);
  EXPECT_NE(capture.response.message.find("view 2 registered"), std::string::npos)
      << capture.response.message;
  // Written: the kept views are forgotten.
  lmk_msgs::AddView forget;
  forget.request.clear = true;
  EXPECT_EQ(call("/lmk_node/add_view", forget).response.views, 0u);

  const ros1::Frame frame = frame_as_the_node_sees_it();
  write_cloud(dir.file("frame.pcd"), frame.scene);
  const Eigen::Quaterniond q(demonstrated.box.pose.linear());
  const Eigen::Vector3d c = demonstrated.box.pose.translation(), size = demonstrated.box.size;
  std::ofstream(dir.file("box.json"))
      << nlohmann::json{{"position", {c.x(), c.y(), c.z()}},
                        {"quaternion", {q.w(), q.x(), q.y(), q.z()}},
                        {"size", {size.x(), size.y(), size.z()}}};
  const auto [code, out] = run_lmk(dir, {"capture", dir.file("frame.pcd"), dir.file("frame.pcd"),
                                         "--box-json", dir.file("box.json"), "--name", "rim", "-o",
                                         dir.file("cli.lmk"), "--base-frame", "--no-check"});
  ASSERT_EQ(code, 0) << out;
  const Landmark by_cli = load_landmark(dir.file("cli.lmk"));
  const Landmark by_node = load_landmark(capture.response.file);
  ASSERT_EQ(by_node.view_count(), 2u);
  EXPECT_EQ(by_node.points.points, by_cli.points.points);
  EXPECT_EQ(by_node.point_views, by_cli.point_views);
  EXPECT_EQ(by_node.view_origins, by_cli.view_origins);
}

// lmk_msgs from Python and the shell (issue #36): `rosservice call` introspects the request and
// answers with the matches, and rospy (examples/ros_find.py) gets the C++ client's answer, match
// for match, error for error.
TEST(LmkNode, RosserviceAndRospyGetTheCppClientsAnswer) {
  FakePr2 robot(fake_settings("demonstration.pcd"));
  const ScratchDir dir;
  fs::create_directories(dir.path() / "landmarks");
  fs::copy_file(demo_data().landmark(), dir.path() / "landmarks" / "rim.lmk");
  const auto node = start_node(dir, dir.file("landmarks"));
  lmk_msgs::FindLandmark find;
  find.request.name = "rim";
  find = call("/lmk_node/find_landmark", find);
  ASSERT_TRUE(find.response.success) << find.response.message;
  ASSERT_FALSE(find.response.matches.empty());

  // The generated Python messages, and lmk_msgs as a package roslib finds.
  setenv("PYTHONPATH", LMK_MSGS_PYTHON_DIR, 1);
  setenv("ROS_PACKAGE_PATH", (std::string(LMK_SOURCE_DIR) + "/ros/msg:/usr/share").c_str(), 1);
  const auto [code, out] =
      run_to_end({"/usr/bin/rosservice", "call", "/lmk_node/find_landmark", "{name: rim}"},
                 dir.file("rosservice.log"));
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("success: True"), std::string::npos) << out;
  std::size_t ranks = 0;
  for (std::size_t at = out.find("rank: "); at != std::string::npos;
       at = out.find("rank: ", at + 1)) {
    ++ranks;
  }
  EXPECT_EQ(ranks, find.response.matches.size()) << out;
  const auto [list_code, listed] =
      run_to_end({"/usr/bin/rosservice", "call", "/lmk_node/list_landmarks"}, dir.file("list.log"));
  ASSERT_EQ(list_code, 0) << listed;
  EXPECT_NE(listed.find("names: \n  - rim"), std::string::npos) << listed;

  const auto [py_code, py_out] = run_to_end(
      {"/usr/bin/python3", std::string(LMK_SOURCE_DIR) + "/examples/ros_find.py", "rim", "--json"},
      dir.file("ros_find.log"));
  ASSERT_EQ(py_code, 0) << py_out;
  const std::size_t line = py_out.find("{\"frame\"");
  ASSERT_NE(line, std::string::npos) << py_out;
  const nlohmann::json answer =
      nlohmann::json::parse(py_out.substr(line, py_out.find('\n', line) - line));
  EXPECT_EQ(answer["frame"], find.response.header.frame_id);
  ASSERT_EQ(answer["matches"].size(), find.response.matches.size());
  for (std::size_t i = 0; i < find.response.matches.size(); ++i) {
    EXPECT_EQ(answer["matches"][i]["rank"].get<std::uint32_t>(), find.response.matches[i].rank);
    EXPECT_EQ(answer["matches"][i]["error"].get<double>(), find.response.matches[i].error);
  }
}

TEST(LmkNode, AClickedPointAndTheMenuCaptureTheGuessedBoxAsInRviz) {
  const Landmark demonstrated = load_landmark(demo_data().landmark().string());
  FakePr2 robot(fake_settings("demonstration.pcd"));
  const ScratchDir dir;
  const auto node = start_node(dir, dir.file("landmarks"));
  const ros1::Frame frame = frame_as_the_node_sees_it();

  // Where a user would click with RViz's Publish Point: on the bowl's rim.
  Eigen::Vector3d click = Eigen::Vector3d::Zero();
  double nearest = 1e9;
  for (const Eigen::Vector3f& p : frame.scene.points) {
    const double d = (p.cast<double>() - demonstrated.box.center()).norm();
    if (is_finite(p) && demonstrated.box.contains(p) && d < nearest) {
      nearest = d;
      click = p.cast<double>();
    }
  }
  ASSERT_LT(nearest, 1e9);
  ::ros::NodeHandle nh;
  ::ros::Publisher clicked = nh.advertise<geometry_msgs::PointStamped>("/clicked_point", 1, true);
  ::ros::Publisher feedback = nh.advertise<visualization_msgs::InteractiveMarkerFeedback>(
      "/lmk_node/capture_box/feedback", 1, true);
  // Publish once the node has connected to both topics: an event, not a time. A latched message
  // published while a subscriber's connection is still being set up aborted this test once, under
  // load, inside roscpp (a null Publication).
  for (int i = 0;
       i < 300 && (clicked.getNumSubscribers() == 0 || feedback.getNumSubscribers() == 0); ++i) {
    ::ros::WallDuration(0.1).sleep();
  }
  geometry_msgs::PointStamped point;
  point.header.frame_id = "base_link";
  point.point.x = click.x();
  point.point.y = click.y();
  point.point.z = click.z();
  clicked.publish(point);
  ::ros::WallDuration(1.0).sleep();  // the node guesses the box

  visualization_msgs::InteractiveMarkerFeedback select;  // what RViz sends for the menu's entry 1
  select.client_id = "/rviz/InteractiveMarkers";
  select.marker_name = "box";
  select.event_type = visualization_msgs::InteractiveMarkerFeedback::MENU_SELECT;
  select.menu_entry_id = 1;  // "Capture as 'landmark'"
  select.header.frame_id = "base_link";
  feedback.publish(select);
  // The bowl is no distinctive landmark in this frame (cups and other bowls match it), so the
  // node refuses it and says why; "even if not distinctive" (entry 2) keeps it.
  const fs::path file = dir.path() / "landmarks" / "landmark.lmk";
  for (int i = 0; i < 300 && node->log().find("not written") == std::string::npos; ++i) {
    ::ros::WallDuration(0.1).sleep();
  }
  EXPECT_NE(node->log().find("not written: it also matches"), std::string::npos) << node->log();
  EXPECT_FALSE(fs::exists(file));
  select.menu_entry_id = 2;
  feedback.publish(select);

  for (int i = 0; i < 300 && !fs::exists(file); ++i) ::ros::WallDuration(0.1).sleep();
  ASSERT_TRUE(fs::exists(file)) << node->log();
  const Landmark captured = load_landmark(file.string());
  const Box expected = guess_box(frame.scene, click).box;
  EXPECT_TRUE(captured.box.pose.isApprox(expected.pose, 1e-9));
  EXPECT_TRUE(captured.box.size.isApprox(expected.size, 1e-9));
}

TEST(LmkNode, BadRequestsAreAnsweredWithTheReason) {
  FakePr2 robot(fake_settings("demonstration.pcd"));
  const ScratchDir dir;
  const auto node = start_node(dir, dir.file("landmarks"));

  lmk_msgs::CaptureLandmark capture;
  capture.request.name = "../outside";
  capture.request.box_pose.pose.orientation.w = 1.0;
  capture.request.box_size.x = capture.request.box_size.y = capture.request.box_size.z = 0.1;
  capture = call("/lmk_node/capture_landmark", capture);
  EXPECT_FALSE(capture.response.success);
  EXPECT_NE(capture.response.message.find("landmark name"), std::string::npos);

  capture.request.name = "tilted";
  capture.request.box_pose.pose.orientation.w = 0.5;  // not a unit quaternion
  capture = call("/lmk_node/capture_landmark", capture);
  EXPECT_FALSE(capture.response.success);
  EXPECT_NE(capture.response.message.find("unit quaternion"), std::string::npos);

  capture.request.box_pose.pose.orientation.w = 1.0;
  capture.request.box_pose.header.frame_id = "no_such_frame";
  capture = call("/lmk_node/capture_landmark", capture);
  EXPECT_FALSE(capture.response.success);
  EXPECT_NE(capture.response.message.find("no_such_frame"), std::string::npos);

  lmk_msgs::FindLandmark find;
  find.request.name = "missing";
  find = call("/lmk_node/find_landmark", find);
  EXPECT_FALSE(find.response.success);
  EXPECT_NE(find.response.message.find("no landmark 'missing'"), std::string::npos);
  EXPECT_TRUE(node->running());
}

// Issue #34, finding 5: with no camera publishing, an infinite box_size was answered "no frame
// yet" after the frame timeout. The request is checked whole first, so the answer names it.
TEST(LmkNode, RequestsAreCheckedBeforeWaitingForAFrame) {
  const ScratchDir dir;  // no FakePr2: no frame ever arrives
  const auto node = start_node(dir, dir.file("landmarks"));
  lmk_msgs::CaptureLandmark capture;
  capture.request.name = "box";
  capture.request.box_pose.pose.orientation.w = 1.0;
  capture.request.box_size.x = std::numeric_limits<double>::infinity();
  capture.request.box_size.y = capture.request.box_size.z = 0.1;
  capture = call("/lmk_node/capture_landmark", capture);
  EXPECT_FALSE(capture.response.success);
  EXPECT_NE(capture.response.message.find("box sides must be positive and finite"),
            std::string::npos)
      << capture.response.message;
  capture.request.box_size.x = 0.1;
  capture.request.name = "-rf";
  capture = call("/lmk_node/capture_landmark", capture);
  EXPECT_NE(capture.response.message.find("not starting with '.' or '-'"), std::string::npos)
      << capture.response.message;

  lmk_msgs::FindLandmark find;
  find.request.name = "missing";
  find = call("/lmk_node/find_landmark", find);
  EXPECT_FALSE(find.response.success);
  EXPECT_NE(find.response.message.find("no landmark 'missing'"), std::string::npos)
      << find.response.message;
  EXPECT_EQ(node->log().find("no frame"), std::string::npos) << node->log();
}

TEST(LmkNode, BadParametersStopItWithOneClearLine) {
  // Each run has a name of its own: parameters stay on the master after a node ends.
  const ScratchDir dir;
  const auto [code, out] = run_to_end({LMK_NODE_BINARY, "__name:=lmk_node_bad",
                                       "_find_settings:={\"selection\": {\"treshold\": 1}}",
                                       "_landmark_directory:=" + dir.file("landmarks")},
                                      dir.file("bad.log"), 60.0);
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("lmk_node: ~find_settings.selection: unknown setting 'treshold'"),
            std::string::npos)
      << out;
  const auto [code2, out2] =
      run_to_end({LMK_NODE_BINARY, "__name:=lmk_node_bad_name", "_capture_name:=../up"},
                 dir.file("bad2.log"), 60.0);
  EXPECT_EQ(code2, 1) << out2;
  EXPECT_NE(out2.find("landmark name '../up'"), std::string::npos) << out2;
  // A number where a JSON string belongs (as a rosparam map would be) is refused, not ignored.
  const auto [code3, out3] =
      run_to_end({LMK_NODE_BINARY, "__name:=lmk_node_bad_type", "_find_settings:=3"},
                 dir.file("bad3.log"), 60.0);
  EXPECT_EQ(code3, 1) << out3;
  EXPECT_NE(out3.find("~find_settings: must be a string of JSON"), std::string::npos) << out3;
  // A depth correction that cannot be read stops the node before it serves a frame uncorrected.
  const auto [code4, out4] = run_to_end({LMK_NODE_BINARY, "__name:=lmk_node_bad_correction",
                                         "_depth_correction:=" + dir.file("missing.json")},
                                        dir.file("bad4.log"), 60.0);
  EXPECT_EQ(code4, 1) << out4;
  EXPECT_NE(out4.find("lmk_node: " + dir.file("missing.json")), std::string::npos) << out4;
  const auto [code5, out5] = run_to_end(
      {LMK_NODE_BINARY, "__name:=lmk_node_bad_frames", "_frames:=31"}, dir.file("bad5.log"), 60.0);
  EXPECT_EQ(code5, 1) << out5;
  EXPECT_NE(out5.find("~frames: must be 1 to 30"), std::string::npos) << out5;
}

}  // namespace
}  // namespace lmk::test
