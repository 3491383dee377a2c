// SPDX-License-Identifier: BSD-3-Clause
// lmk_node: finds and captures landmarks in a robot's camera frames over ROS 1 (docs/ros.md).
#include <ros/ros.h>

#include "lmk/geometry/error.h"
#include "lmk/geometry/memory_reuse.h"
#include "lmk/ros/landmark_node.h"

int main(int argc, char** argv) {
  lmk::keep_freed_memory_for_reuse();  // a search per frame: its buffers kept for the next
  ros::init(argc, argv, "lmk_node");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  try {
    lmk::ros1::LandmarkNode node(nh, private_nh,
                                 lmk::ros1::LandmarkNodeSettings::from_parameters(private_nh));
    // Two threads: a long search must not stall the camera subscription behind it.
    ros::MultiThreadedSpinner spinner(2);
    spinner.spin();
  } catch (const lmk::Error& e) {
    ROS_FATAL("lmk_node: %s", e.what());
    return 1;
  }
  return 0;
}
