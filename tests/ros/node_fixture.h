// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What the ROS end-to-end tests share (node_test.cpp: lmk_node's services; pbd_run_on_ros_test.cpp:
// `lmk pbd run --ros` and RosRobot): the paper's task 3 from lmk's demo tasks, written once per
// test process, the fake PR2 on one of its frames, the frame as the node builds it, and the node
// and the CLI as child processes. Every test process starts its own rosmaster (ros_harness.h).

#include <ros/ros.h>

#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lmk/geometry/point_cloud.h"
#include "lmk/ros/latest_frame.h"
#include "tests/ros/support/fake_pr2.h"
#include "tests/ros/support/ros_harness.h"
#include "tests/support/test_support.h"

namespace lmk::test {

/// Task 3 of the demo tasks ("bowls on a shelf"): its scenes, its landmark and its program.
struct DemoData {
  std::filesystem::path task;
  PointCloud scene(const std::string& file) const;
  std::filesystem::path landmark() const { return task / "bowl_rim.lmk"; }
  std::filesystem::path program() const { return task / "pick_bowl.json"; }
};

/// Written once per CTest run (test::shared_run_data): each test is a process of its own, and the
/// tests only read it.
const DemoData& demo_data();

/// The fake PR2 on task 3's frame `scene_file`, its torso as the task's.
FakePr2Settings fake_settings(const std::string& scene_file);

/// The frame lmk_node and `lmk pbd run --ros` build from the fake's camera: the same message and
/// the same TF, through the same conversion, so the same points bit for bit.
ros1::Frame frame_as_the_node_sees_it();

/// lmk_node on the landmark directory `landmarks`, with `parameters` ("_name:=value"); a test
/// failure with its log if its services do not come up.
std::unique_ptr<ChildProcess> start_node(const ScratchDir& dir, const std::string& landmarks,
                                         const std::vector<std::string>& parameters = {});

/// Runs the lmk CLI to its end; its exit code and output.
std::pair<int, std::string> run_lmk(const ScratchDir& dir, std::vector<std::string> args);

/// Calls the service `name`, a test failure if the call fails; the service with its response.
template <class Service>
Service call(const std::string& name, Service service) {
  EXPECT_TRUE(::ros::service::call(name, service)) << name;
  return service;
}

}  // namespace lmk::test
