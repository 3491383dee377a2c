// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// TF lookups as lmk poses: T_target_source, the pose of `source` in `target`.

#include <ros/duration.h>
#include <ros/time.h>
#include <tf2_ros/buffer.h>

#include <Eigen/Geometry>
#include <string>

namespace lmk::ros1 {

/// T_target_source at `time` (ros::Time(0): the latest), waiting up to `timeout` for TF to have it.
/// Throws lmk::Error with TF's own reason (unknown frame, no path, extrapolation).
Eigen::Isometry3d lookup_pose(const tf2_ros::Buffer& tf, const std::string& target,
                              const std::string& source, const ::ros::Time& time,
                              const ::ros::Duration& timeout);

}  // namespace lmk::ros1
