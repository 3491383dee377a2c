// SPDX-License-Identifier: BSD-3-Clause
// A catkin package's client of lmk_node: fills a find_landmark request from lmk's installed
// lmk_msgs headers and converts a pose with lmk::ros, without a running master.
#include <lmk_msgs/FindLandmark.h>

#include <cstdio>

#include "lmk/ros/geometry_conversion.h"

int main() {
  lmk_msgs::FindLandmark find;
  find.request.name = "milk";
  const geometry_msgs::Pose pose = lmk::ros1::to_ros(Eigen::Isometry3d::Identity());
  std::printf("lmk_msgs/FindLandmark %s for '%s'; identity pose w = %.1f\n",
              ros::service_traits::md5sum(find), find.request.name.c_str(), pose.orientation.w);
  return pose.orientation.w == 1.0 ? 0 : 1;
}
