// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// sensor_msgs/PointCloud2 to and from lmk::PointCloud (docs/ros.md, "Conversions").
//
// A depth camera's cloud is organised (width x height, row-major) with NaN where the sensor had no
// return; both directions keep the grid and the NaNs, so that lmk's sensor metric and range images
// see the frame as the camera took it. Colour travels as the packed 32-bit "rgb" or "rgba" field
// that PCL, RViz and the Kinect drivers use; labels as an int32 or uint32 "label" field.

#include <sensor_msgs/PointCloud2.h>

#include <string>

#include "lmk/geometry/point_cloud.h"

namespace lmk::ros1 {

/// The cloud in its own frame (msg.header.frame_id), read as lmk reads a PCD file's points
/// (geometry/point_records.h): x, y, z of any numeric type, normals, "rgba" or "rgb" and "label"
/// when present; every other field is ignored. The sensor is placed at the frame's origin
/// (T_cloud_sensor = identity), which holds for a camera's optical frame; a node that knows better
/// sets it from TF. Throws lmk::Error naming `what` for a cloud without x, y, z, with big-endian
/// data, with a field beyond its point step, or whose sizes disagree with its data.
PointCloud from_ros(const sensor_msgs::PointCloud2& msg, const std::string& what = "PointCloud2");

/// FLOAT32 x, y, z, plus a packed "rgb" when the cloud has colours and an INT32 "label" when it has
/// labels; organised clouds stay organised, and is_dense says whether every point is finite.
sensor_msgs::PointCloud2 to_ros(const PointCloud& cloud, const std::string& frame_id);

}  // namespace lmk::ros1
