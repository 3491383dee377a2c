// SPDX-License-Identifier: BSD-3-Clause
#include "tests/ros/node_fixture.h"

#include <gtest/gtest.h>
#include <ros/topic.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <stdexcept>

#include "lmk/demos/demo_tasks.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/ros/cloud_conversion.h"
#include "tests/support/test_support.h"

namespace lmk::test {
namespace {

// Each test process starts its own rosmaster on a free port, before its first test.
const bool kRosMaster = (use_ros_master("lmk_ros_test"), true);

}  // namespace

PointCloud DemoData::scene(const std::string& file) const {
  return read_cloud((task / file).string());
}

const DemoData& demo_data() {
  static const DemoData data{shared_run_data("demo-task3",
                                             [](const std::filesystem::path& dir) {
                                               DemoTasksSettings settings;
                                               settings.tasks = {3};
                                               settings.save_dir = dir.string();
                                               run_demo_tasks(settings);
                                             }) /
                             "task3"};
  return data;
}

FakePr2Settings fake_settings(const std::string& scene_file) {
  FakePr2Settings s;
  s.scene = demo_data().scene(scene_file);
  s.torso_height = 0.0;  // task 3's
  return s;
}

ros1::Frame frame_as_the_node_sees_it() {
  static tf2_ros::Buffer tf;
  static tf2_ros::TransformListener listener(tf);
  const auto msg = ::ros::topic::waitForMessage<sensor_msgs::PointCloud2>(
      "/head_mount_kinect/depth_registered/points", ::ros::Duration(20));
  if (!msg) throw std::runtime_error("the fake PR2 publishes no cloud");
  return ros1::frame_from_cloud(*msg, tf, "base_link", "", ::ros::Duration(2.0));
}

std::unique_ptr<ChildProcess> start_node(const ScratchDir& dir, const std::string& landmarks,
                                         const std::vector<std::string>& parameters) {
  std::vector<std::string> args{LMK_NODE_BINARY, "__name:=lmk_node",
                                "_landmark_directory:=" + landmarks};
  args.insert(args.end(), parameters.begin(), parameters.end());
  auto node = std::make_unique<ChildProcess>(args, dir.file("lmk_node.log"));
  if (!::ros::service::waitForService("/lmk_node/find_landmark", ::ros::Duration(30))) {
    ADD_FAILURE() << "lmk_node did not come up:\n" << node->log();
  }
  return node;
}

std::pair<int, std::string> run_lmk(const ScratchDir& dir, std::vector<std::string> args) {
  args.insert(args.begin(), LMK_BINARY);
  return run_to_end(args, dir.file("lmk.log"));
}

}  // namespace lmk::test
