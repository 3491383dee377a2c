// SPDX-License-Identifier: BSD-3-Clause
// lmk on ROS 1, end to end against a real rosmaster of the test's own (tests/ros/support):
// lmk_node's services on a fake PR2's camera, `lmk pbd run --ros` driving the fake PR2's
// controllers, and RosRobot's lifecycle. The scenes, landmark and program are the paper's task 3
// ("bowls on a shelf") from lmk's demo tasks: its demonstration frame, a frame where the bowl can
// be picked, and one with only cups, where the robot must not act.
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
#include "tests/ros/support/fake_pr2.h"
#include "tests/ros/support/ros_harness.h"
#include "tests/support/lifecycle_conformance.h"
#include "tests/support/test_support.h"

namespace lmk::test {
namespace {

namespace fs = std::filesystem;

const bool kRosMaster = (use_ros_master("lmk_ros_test"), true);

/// Task 3 of the demo tasks, written once per test process.
struct DemoData {
  ScratchDir dir;
  fs::path task;
  PointCloud scene(const std::string& file) const { return read_cloud((task / file).string()); }
  fs::path landmark() const { return task / "bowl_rim.lmk"; }
  fs::path program() const { return task / "pick_bowl.json"; }
};

const DemoData& demo_data() {
  static const DemoData* data = [] {
    auto* d = new DemoData;
    DemoTasksSettings settings;
    settings.tasks = {3};
    settings.save_dir = d->dir.path().string();
    run_demo_tasks(settings);
    d->task = d->dir.path() / "task3";
    return d;
  }();
  return *data;
}

FakePr2Settings fake_settings(const std::string& scene_file) {
  FakePr2Settings s;
  s.scene = demo_data().scene(scene_file);
  s.torso_height = 0.0;  // task 3's
  return s;
}

/// The frame lmk_node and `lmk pbd run --ros` build from the fake's camera: the same message and
/// the same TF, through the same conversion, so the same points bit for bit.
ros1::Frame frame_as_the_node_sees_it() {
  static tf2_ros::Buffer tf;
  static tf2_ros::TransformListener listener(tf);
  const auto msg = ::ros::topic::waitForMessage<sensor_msgs::PointCloud2>(
      "/head_mount_kinect/depth_registered/points", ::ros::Duration(20));
  if (!msg) throw std::runtime_error("the fake PR2 publishes no cloud");
  return ros1::frame_from_cloud(*msg, tf, "base_link", "", ::ros::Duration(2.0));
}

std::unique_ptr<ChildProcess> start_node(const ScratchDir& dir, const std::string& landmarks,
                                         const std::vector<std::string>& parameters = {}) {
  std::vector<std::string> args{LMK_NODE_BINARY, "__name:=lmk_node",
                                "_landmark_directory:=" + landmarks};
  args.insert(args.end(), parameters.begin(), parameters.end());
  auto node = std::make_unique<ChildProcess>(args, dir.file("lmk_node.log"));
  if (!::ros::service::waitForService("/lmk_node/find_landmark", ::ros::Duration(30))) {
    ADD_FAILURE() << "lmk_node did not come up:\n" << node->log();
  }
  return node;
}

/// Runs the lmk CLI to its end; its exit code and output.
std::pair<int, std::string> run_lmk(const ScratchDir& dir, std::vector<std::string> args) {
  args.insert(args.begin(), LMK_BINARY);
  return run_to_end(args, dir.file("lmk.log"));
}

template <class Service>
Service call(const std::string& name, Service service) {
  EXPECT_TRUE(::ros::service::call(name, service)) << name;
  return service;
}

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

/// The plan `lmk pbd run --ros` makes: the same frame, joint state, torso and settings.
Plan expected_plan(const FakePr2& robot) {
  const Program program = load_program(demo_data().program().string());
  const auto landmarks = load_program_landmarks(program, demo_data().task.string());
  JointState state;
  for (const auto& [name, q] : robot.joints()) {
    state.names.push_back(name);
    state.positions.push_back(q);
    state.velocities.push_back(0.0);
  }
  const Pr2Kinematics kinematics(RobotModel::pr2(), 0.0);
  return plan(program, landmarks, frame_as_the_node_sees_it().scene, kinematics, state);
}

const char* arm_action(Arm arm) {
  return arm == Arm::kLeft ? "l_arm_controller/joint_trajectory_action"
                           : "r_arm_controller/joint_trajectory_action";
}

TEST(PbdRunOnRos, DrivesThePr2WithExactlyThePlannedTrajectories) {
  FakePr2 robot(fake_settings("scenario3.pcd"));
  const Plan plan = expected_plan(robot);
  ASSERT_TRUE(plan.valid()) << describe(*plan.refusal);
  ASSERT_FALSE(plan.steps.empty());
  const ScratchDir dir;
  // Unchecked, as the plan above: the checked run's goals are another test's.
  const auto [code, out] = run_lmk(
      dir, {"pbd", "run", demo_data().program().string(), "--ros", "--no-check-collisions"});
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("done"), std::string::npos) << out;

  std::map<std::string, std::size_t> next;
  for (const PlannedStep& step : plan.steps) {
    for (const PlannedArm& a : step.arms) {
      const auto sent = robot.trajectories(arm_action(a.arm));
      const std::size_t k = next[arm_action(a.arm)]++;
      ASSERT_LT(k, sent.size()) << "step " << step.index << ": no goal for " << arm_name(a.arm);
      const trajectory_msgs::JointTrajectory& got = sent[k];
      EXPECT_EQ(got.joint_names, a.trajectory.joint_names);
      ASSERT_EQ(got.points.size(), a.trajectory.points.size());
      for (std::size_t p = 0; p < got.points.size(); ++p) {
        EXPECT_EQ(got.points[p].positions, a.trajectory.points[p].positions);
        EXPECT_NEAR(got.points[p].time_from_start.toSec(), a.trajectory.points[p].time_from_start,
                    1e-9);
      }
    }
  }
  ASSERT_FALSE(next.empty());
  for (const auto& [action, used] : next) EXPECT_EQ(robot.goals(action), static_cast<int>(used));
  // Each step's gripper too, on the arm that moved.
  EXPECT_EQ(robot.goals("r_gripper_controller/gripper_action"),
            static_cast<int>(next["r_arm_controller/joint_trajectory_action"]));
}

int arm_and_gripper_goals(const FakePr2& robot) {
  return robot.total_goals() - robot.goals("head_traj_controller/point_head_action");
}

TEST(PbdRunOnRos, AMissingLandmarkSendsNoArmGoalAfterLookingAgain) {
  FakePr2 robot(fake_settings("scenario5.pcd"));  // only cups
  const ScratchDir dir;
  // The head looks twice (--look-again's default), sees no bowl either time, and the run refuses
  // naming both looks.
  const auto [code, out] = run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros"});
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("refused: landmark 'bowl_rim' not found"), std::string::npos) << out;
  EXPECT_NE(out.find("after 2 more looks (at ("), std::string::npos) << out;
  EXPECT_EQ(robot.goals("head_traj_controller/point_head_action"), 2);
  EXPECT_EQ(arm_and_gripper_goals(robot), 0);
  // --look-again 0 refuses at once: not even the head moves.
  const auto [code2, out2] =
      run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros", "--look-again", "0"});
  EXPECT_EQ(code2, 1) << out2;
  EXPECT_EQ(out2.find("more look"), std::string::npos) << out2;
  EXPECT_EQ(robot.goals("head_traj_controller/point_head_action"), 2);
  EXPECT_EQ(arm_and_gripper_goals(robot), 0);
}

TEST(PbdRunOnRos, AMotionThatWouldTouchAndCannotGoAroundSendsNoArmGoal) {
  FakePr2 robot(fake_settings("scenario3.pcd"));  // the bowl is there: only the motion refuses
  const ScratchDir dir;
  // 20 cm of padding from the shelf and a planner allowed one configuration: the first motion
  // would come too near, and no way around it is found. Nothing moves, not even the head.
  const auto [code, out] =
      run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros", "--check-collisions",
                    "--padding", "0.2", "--planning-checks", "1", "--look-again", "0",
                    "--unseen-looks", "0"});
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("refused: step 0, right arm: link "), std::string::npos) << out;
  EXPECT_NE(out.find(" m in base_link"), std::string::npos) << out;
  EXPECT_EQ(robot.total_goals(), 0);
}

TEST(PbdRunOnRos, TheCollisionModelIsReadFromRobotDescription) {
  FakePr2 robot(fake_settings("scenario3.pcd"));
  struct Param {  // a parameter for this test only, whatever fails
    Param(std::string name, const std::string& value) : name_(std::move(name)) {
      ::ros::param::set(name_, value);
    }
    ~Param() { ::ros::param::del(name_); }
    std::string name_;
  };
  const ScratchDir dir;
  const std::vector<std::string> run = {"pbd", "run", demo_data().program().string(), "--ros",
                                        "--check-collisions"};
  std::ifstream in(std::string(LMK_SOURCE_DIR) + "/pr2/data/pr2.urdf");
  const std::string urdf(std::istreambuf_iterator<char>(in), {});
  {
    // With MoveIt's SRDF beside it: its pairs of links that may touch are taken.
    const Param pr2("/robot_description", urdf);
    const Param semantic("/robot_description_semantic", R"(<robot name="pr2">
      <disable_collisions link1="r_gripper_palm_link" link2="l_gripper_palm_link"/>
      <disable_collisions link1="r_forearm_link" link2="l_forearm_link"/></robot>)");
    const auto [code, out] = run_lmk(dir, run);
    EXPECT_EQ(code, 0) << out;
    EXPECT_NE(out.find("collision model: robot_description's pr2, "), std::string::npos) << out;
    EXPECT_NE(out.find("2 pairs of links that may touch from robot_description_semantic"),
              std::string::npos)
        << out;
  }
  const int goals = robot.total_goals();
  for (const auto& [name, value, said] :
       {std::tuple<std::string, std::string, std::string>{
            "/robot_description", "<robot name=\"broken\"></robot>", "robot_description"},
        {"/robot_description_semantic", "<robot><disable_collisions link1=\"a\"/></robot>",
         "robot_description_semantic: a <disable_collisions> element"}}) {
    // A description that is no robot, an SRDF that is broken: one clear line, nothing moves.
    const Param description("/robot_description", urdf);
    const Param broken(name, value);
    const auto [code, out] = run_lmk(dir, run);
    EXPECT_EQ(code, 2) << out;
    EXPECT_NE(out.find("pbd run --ros: "), std::string::npos) << out;
    EXPECT_NE(out.find(said), std::string::npos) << out;
    EXPECT_EQ(robot.total_goals(), goals);
  }
}

/// The PR2's arms as the fake PR2 starts them: every joint at zero, or at its nearest limit.
JointState arms_at_rest(const Pr2Kinematics& kinematics) {
  JointState state;
  for (const char* group : {"left_arm", "right_arm"}) {
    const GroupInfo info = *kinematics.group(group);  // alive while its joints are read
    for (const JointInfo& j : info.joints) {
      state.names.push_back(j.name);
      state.positions.push_back(j.continuous() ? 0.0 : std::clamp(0.0, j.lower, j.upper));
      state.velocities.push_back(0.0);
    }
  }
  return state;
}

/// `scene` as a camera whose image ends before `box`: every pixel on the box's side of the image,
/// from the box's nearest corner on, returns nothing.
PointCloud cut_by_the_image_edge(const PointCloud& scene, const Box& box) {
  const Eigen::Isometry3d T_sensor_cloud = scene.T_cloud_sensor.inverse();
  const double side = (T_sensor_cloud * box.pose.translation()).x() > 0.0 ? 1.0 : -1.0;
  double edge = std::numeric_limits<double>::infinity();  // in x/z, the image's column
  for (const Eigen::Vector3d& corner : box.corners()) {
    const Eigen::Vector3d c = T_sensor_cloud * corner;
    edge = std::min(edge, side * c.x() / c.z());
  }
  PointCloud cut = scene;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < cut.size(); ++i) {
    const Eigen::Vector3d p = T_sensor_cloud * cut.points[i].cast<double>();
    if (std::isfinite(p.z()) && side * p.x() / p.z() >= edge - 0.02) {
      cut.points[i].setConstant(nan);
      if (cut.has_normals()) cut.normals[i].setConstant(nan);
    }
  }
  return cut;
}

// Looking again (issue #46): the first view's image ends before the bowl; the head turns, the
// camera then sees it whole, the new frame is fused with the first and the program runs.
TEST(PbdRunOnRos, ALandmarkTheFirstViewCutIsFoundByLookingAgain) {
  const PointCloud whole = demo_data().scene("scenario3.pcd");
  const Program program = load_program(demo_data().program().string());
  const auto landmarks = load_program_landmarks(program, demo_data().task.string());
  const Pr2Kinematics kinematics(RobotModel::pr2(), 0.0);
  const JointState rest = arms_at_rest(kinematics);
  const Plan in_whole = plan(program, landmarks, whole, kinematics, rest);
  ASSERT_TRUE(in_whole.valid()) << describe(*in_whole.refusal);
  const LocatedLandmark* bowl = in_whole.landmark("bowl_rim");
  ASSERT_NE(bowl, nullptr);
  const PointCloud cut = cut_by_the_image_edge(whole, bowl->match.box);
  // The cut frame alone does not show the bowl: without looking again the robot would refuse.
  const Plan in_cut = plan(program, landmarks, cut, kinematics, rest);
  ASSERT_FALSE(in_cut.valid());
  ASSERT_TRUE(std::holds_alternative<LandmarkNotFound>(*in_cut.refusal))
      << describe(*in_cut.refusal);

  FakePr2Settings settings = fake_settings("scenario3.pcd");
  settings.scene = cut;
  settings.scenes_after_head_goals = {whole};
  FakePr2 robot(settings);
  const ScratchDir dir;
  // Unchecked: the head's one look is the landmark's, none where the arm would go.
  const auto [code, out] = run_lmk(
      dir, {"pbd", "run", demo_data().program().string(), "--ros", "--no-check-collisions"});
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("looked again at ("), std::string::npos) << out;
  EXPECT_NE(out.find("for the missing 'bowl_rim'"), std::string::npos) << out;
  EXPECT_NE(out.find("done"), std::string::npos) << out;
  EXPECT_EQ(robot.goals("head_traj_controller/point_head_action"), 1);
  EXPECT_GT(robot.goals("r_arm_controller/joint_trajectory_action") +
                robot.goals("l_arm_controller/joint_trajectory_action"),
            0);
}

TEST(PbdRunOnRos, AnAbortedArmGoalStopsTheRunAndNamesTheStep) {
  FakePr2 robot(fake_settings("scenario3.pcd"));
  robot.abort_arm_goal(2);
  const ScratchDir dir;
  const auto [code, out] = run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros"});
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("stopped after 1 of"), std::string::npos) << out;
  EXPECT_NE(out.find("step 1: right_arm: r_arm_controller/joint_trajectory_action: the "
                     "controller aborted the goal (fake PR2: the test asked for an abort)"),
            std::string::npos)
      << out;
  int arm_goals = 0;
  for (Arm arm : {Arm::kLeft, Arm::kRight}) arm_goals += robot.goals(arm_action(arm));
  EXPECT_EQ(arm_goals, 2);  // nothing after the abort
}

// The boxes of the bowls lmk finds in `scene` (base_link), each grown by 4 cm on every side: what
// a person who takes or moves a bowl takes along (the table under it too).
std::vector<Box> around_the_bowls(const PointCloud& scene) {
  FindSettings find;
  find.scene.base_frame = true;
  const FindResult bowls =
      find_landmark(scene, load_landmark(demo_data().landmark().string()), find);
  std::vector<Box> around;
  for (const Match& bowl : bowls.matches)
    around.emplace_back(bowl.box.pose, bowl.box.size + Eigen::Vector3d::Constant(0.08));
  return around;
}

bool in_any(const std::vector<Box>& boxes, const Eigen::Vector3f& p) {
  return std::any_of(boxes.begin(), boxes.end(), [&](const Box& b) { return b.contains(p); });
}

// `scene` (organised) with the points in `moved` shifted by `shift`, as its camera would see it
// then: every point projected onto its pixel again, the nearest kept.
PointCloud seen_after_moving(const PointCloud& scene, const std::vector<Box>& moved,
                             const Eigen::Vector3f& shift) {
  const std::optional<RangeImage> image = RangeImage::from_cloud(scene);
  EXPECT_TRUE(image && image->organised());
  PointCloud out = scene;
  std::fill(out.points.begin(), out.points.end(),
            Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN()));
  std::vector<float> nearest(scene.size(), std::numeric_limits<float>::infinity());
  const Eigen::Vector3f sensor = scene.sensor_origin().cast<float>();
  for (std::size_t i = 0; i < scene.size(); ++i) {
    Eigen::Vector3f p = scene.points[i];
    if (!p.allFinite()) continue;
    if (in_any(moved, p)) p += shift;
    const std::optional<Eigen::Vector2d> pixel = image->project(p);
    if (!pixel) continue;
    const long u = std::lround(pixel->x()), v = std::lround(pixel->y());
    if (u < 0 || v < 0 || u >= static_cast<long>(scene.width) ||
        v >= static_cast<long>(scene.height))
      continue;
    const std::size_t k = static_cast<std::size_t>(v) * scene.width + static_cast<std::size_t>(u);
    const float range = (p - sensor).norm();
    if (range >= nearest[k]) continue;
    nearest[k] = range;
    out.points[k] = p;
    if (!scene.colors.empty()) out.colors[k] = scene.colors[i];
  }
  return out;
}

// Where the right gripper ends the `n`-th (0-based) trajectory the fake PR2 received.
Eigen::Vector3d right_gripper_after(const FakePr2& robot, std::size_t n) {
  const auto sent = robot.trajectories(arm_action(Arm::kRight));
  EXPECT_LT(n, sent.size());
  if (n >= sent.size()) return Eigen::Vector3d::Constant(std::nan(""));
  const Pr2Kinematics kinematics(RobotModel::pr2(), 0.0);
  const GroupInfo arm = *kinematics.group("right_arm");
  std::vector<double> joints;
  for (const JointInfo& j : arm.joints) {
    const auto& names = sent[n].joint_names;
    const auto at = std::find(names.begin(), names.end(), j.name);
    EXPECT_NE(at, names.end()) << j.name;
    if (at == names.end()) return Eigen::Vector3d::Constant(std::nan(""));
    joints.push_back(sent[n].points.back().positions[at - names.begin()]);
  }
  Eigen::Isometry3d T_base_tool;
  EXPECT_TRUE(kinematics.forward("right_arm", joints, T_base_tool).ok());
  return T_base_tool.translation();
}

TEST(PbdRunOnRos, WatchingReplansWhenTheLandmarkIsMovedWhileTheArmMoves) {
  // pick_bowl: approach, grasp and lift relative to the bowl, then a place in the base frame. The
  // bowls are pushed 5 cm to the robot's left once the approach is under way.
  FakePr2Settings settings = fake_settings("scenario1.pcd");
  const std::vector<Box> bowls = around_the_bowls(settings.scene);
  ASSERT_FALSE(bowls.empty());
  const Eigen::Vector3f push(0.0f, 0.05f, 0.0f);
  settings.scenes_after_arm_goals = {seen_after_moving(settings.scene, bowls, push)};

  const ScratchDir dir;
  Eigen::Vector3d grasp_watched;
  {
    FakePr2 robot(settings);
    const auto [code, out] =
        run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros", "--watch"});
    ASSERT_EQ(code, 0) << out;
    EXPECT_NE(out.find("re-planned the remaining"), std::string::npos) << out;
    // Noticed before the approach's gripper command: the approach again towards the bowl where it
    // is now, then grasp, lift and place.
    const auto sent = robot.trajectories(arm_action(Arm::kRight));
    ASSERT_EQ(sent.size(), 5u) << out;
    grasp_watched = right_gripper_after(robot, 2);
  }
  FakePr2 robot(settings);
  const auto [code, out] = run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros"});
  ASSERT_EQ(code, 0) << out;  // open loop: it grasps where the bowl was
  ASSERT_EQ(robot.trajectories(arm_action(Arm::kRight)).size(), 4u) << out;
  const Eigen::Vector3d grasp_open_loop = right_gripper_after(robot, 1);
  // The watched grasp followed the bowl; the open-loop one did not.
  const Eigen::Vector3d followed = grasp_watched - grasp_open_loop;
  EXPECT_NEAR(followed.y(), push.y(), 0.01) << followed.transpose();
  EXPECT_LT(std::hypot(followed.x(), followed.z()), 0.01) << followed.transpose();
}

// Issue #48, --watch: the bowl is taken away once the arm has its first goal. Watching, the run
// notices before the gripper moves and stops, sending nothing more; unwatched, it goes on.
TEST(PbdRunOnRos, WatchingStopsWhenTheLandmarkIsTakenWhileTheArmMoves) {
  FakePr2Settings settings = fake_settings("scenario1.pcd");
  // The scene without its bowls: every instance's box emptied (with one left, the watch would
  // rightly follow the program to it).
  const std::vector<Box> bowls = around_the_bowls(settings.scene);
  ASSERT_FALSE(bowls.empty());
  PointCloud taken = settings.scene;
  for (Eigen::Vector3f& p : taken.points) {
    if (p.allFinite() && in_any(bowls, p)) p.setConstant(std::numeric_limits<float>::quiet_NaN());
  }
  settings.scenes_after_arm_goals = {taken};

  const ScratchDir dir;
  {
    FakePr2 robot(settings);
    const auto [code, out] =
        run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros", "--watch"});
    EXPECT_EQ(code, 1) << out;
    EXPECT_NE(out.find("landmark 'bowl_rim' is lost: stopped rather than move towards where it "
                       "was"),
              std::string::npos)
        << out;
    int arm_goals = 0;
    for (Arm arm : {Arm::kLeft, Arm::kRight}) arm_goals += robot.goals(arm_action(arm));
    EXPECT_EQ(arm_goals, 1);  // the first only: no arm goal after the bowls went
  }
  FakePr2 robot(settings);
  const auto [code, out] = run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros"});
  EXPECT_EQ(code, 0) << out;  // open loop: it never looked again, and went on
  int arm_goals = 0;
  for (Arm arm : {Arm::kLeft, Arm::kRight}) arm_goals += robot.goals(arm_action(arm));
  EXPECT_GT(arm_goals, 1);
}

TEST(PbdRunOnRos, NoMasterOrNoRobotIsOneClearLine) {
  const ScratchDir dir;
  const auto [code, out] = run_to_end({"env", "ROS_MASTER_URI=http://127.0.0.1:1/", LMK_BINARY,
                                       "pbd", "run", demo_data().program().string(), "--ros"},
                                      dir.file("no_master.log"));
  EXPECT_EQ(code, 2) << out;
  EXPECT_NE(out.find("lmk: error: pbd run --ros: no ROS master at http://127.0.0.1:1/"),
            std::string::npos)
      << out;
  // A master, but no robot: configure names every controller and topic that did not answer.
  const auto [code2, out2] = run_lmk(dir, {"pbd", "run", demo_data().program().string(), "--ros"});
  EXPECT_EQ(code2, 2) << out2;
  EXPECT_NE(out2.find("lmk: error: pbd run --ros: configure: no answer within 5.0 s from "
                      "l_arm_controller/joint_trajectory_action"),
            std::string::npos)
      << out2;
}

TEST(RosRobot, AnswersEveryMethodInEveryStateAsTheInterfaceDocuments) {
  FakePr2 fake(fake_settings("demonstration.pcd"));
  ros1::RosRobot robot{::ros::NodeHandle()};
  expect_lifecycle_table(robot, *Pr2Kinematics().group("left_arm"), "left");
  EXPECT_GE(fake.goals("l_arm_controller/joint_trajectory_action"), 1);
}

TEST(RosRobot, AGoalWithoutResultInTimeIsCancelledAndReturnedAsAnError) {
  FakePr2 fake(fake_settings("demonstration.pcd"));
  fake.hang_arm_goal(1);
  ros1::RosRobotSettings settings;
  settings.result_margin = 1.0;
  ros1::RosRobot robot(::ros::NodeHandle(), settings);
  ASSERT_TRUE(robot.configure().ok());
  ASSERT_TRUE(robot.activate().ok());
  JointTrajectory hold;
  JointTrajectory::Point point;
  const std::map<std::string, double> joints = fake.joints();
  const GroupInfo arm = *Pr2Kinematics().group("right_arm");  // alive while its joints are read
  for (const JointInfo& j : arm.joints) {
    hold.joint_names.push_back(j.name);
    point.positions.push_back(joints.at(j.name));
  }
  point.time_from_start = 0.5;
  hold.points.push_back(point);
  const CallResult r = robot.send_trajectory("right_arm", hold);  // 0.5 s + 1 s margin
  EXPECT_EQ(r.status, Status::kError);
  EXPECT_NE(r.message.find("r_arm_controller/joint_trajectory_action: no result within 1.5 s; "
                           "the goal was cancelled"),
            std::string::npos)
      << r.message;
  for (int i = 0; i < 200 && fake.cancelled_goals() == 0; ++i) ::ros::WallDuration(0.01).sleep();
  EXPECT_EQ(fake.cancelled_goals(), 1);
  EXPECT_EQ(robot.state(), LifecycleState::kActive);
  EXPECT_TRUE(robot.send_trajectory("right_arm", hold).ok());  // the next goal runs
}

TEST(RosRobot, ARejectedGoalIsReturnedAsAnError) {
  FakePr2 fake(fake_settings("demonstration.pcd"));
  // A controller that rejects every goal, standing in for the right arm's.
  using Server = actionlib::ActionServer<pr2_controllers_msgs::JointTrajectoryAction>;
  ::ros::NodeHandle nh;
  // The server's callbacks run on a queue of its own, whose spinner is destroyed before the server
  // (declared after it): ~RosRobot cancels its goals, and on the global queue that cancel could
  // reach the server while it is destroyed, which aborted roscpp ('null Publication').
  ::ros::CallbackQueue strict_queue;
  ::ros::NodeHandle strict_nh;
  strict_nh.setCallbackQueue(&strict_queue);
  Server strict(
      strict_nh, "strict_arm/joint_trajectory_action",
      [](Server::GoalHandle goal) {
        goal.setRejected(pr2_controllers_msgs::JointTrajectoryResult(), "joints out of range");
      },
      false);
  strict.start();
  ::ros::AsyncSpinner strict_spinner(1, &strict_queue);
  strict_spinner.start();
  ros1::RosRobotSettings settings;
  settings.arm_actions = {{"left_arm", "l_arm_controller/joint_trajectory_action"},
                          {"right_arm", "strict_arm/joint_trajectory_action"}};
  ros1::RosRobot robot(nh, settings);
  ASSERT_TRUE(robot.configure().ok());
  ASSERT_TRUE(robot.activate().ok());
  JointTrajectory t;
  t.joint_names = {"r_shoulder_pan_joint"};
  t.points.push_back({{0.0}, 1.0});
  const CallResult r = robot.send_trajectory("right_arm", t);
  EXPECT_EQ(r.status, Status::kError);
  EXPECT_EQ(r.message,
            "strict_arm/joint_trajectory_action: the controller rejected the goal (joints out of "
            "range)");
}

TEST(RosRobot, ConfigureNamesWhatDoesNotAnswer) {
  ros1::RosRobotSettings settings;
  settings.connect_timeout = 1.0;
  ros1::RosRobot robot(::ros::NodeHandle(), settings);
  const CallResult r = robot.configure();
  EXPECT_EQ(r.status, Status::kError);
  EXPECT_NE(r.message.find("l_arm_controller/joint_trajectory_action"), std::string::npos)
      << r.message;
  EXPECT_NE(r.message.find("joint_states"), std::string::npos) << r.message;
  EXPECT_EQ(robot.state(), LifecycleState::kUnconfigured);
}

}  // namespace
}  // namespace lmk::test
