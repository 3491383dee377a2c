// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The latest frame of a depth camera, in the robot's base frame: what lmk_node captures from and
// searches in. The cloud is moved into the base frame with TF at its own stamp, and its sensor is
// placed where TF says the camera was, so that the empty-space and sensor metrics see the real
// viewpoint (docs/ros.md).

#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/buffer.h>

#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/depth_correction.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk::ros1 {

struct Frame {
  PointCloud scene;         ///< in the base frame; T_cloud_sensor is T_base_sensor
  std::string base_frame;   ///< the frame `scene` is in
  std::string cloud_frame;  ///< the frame the camera published it in
  ::ros::Time stamp;        ///< when the camera took it
};

/// Converts one PointCloud2 into a Frame in `base_frame`. `sensor_frame` is the camera's optical
/// frame; empty, the cloud's own frame is taken to be it. A `correction` (the camera's depth
/// error, lmk calibrate-depth) is undone first, in the camera's frame. Throws lmk::Error for a
/// malformed cloud, a missing transform or a cloud the correction does not fit.
Frame frame_from_cloud(const sensor_msgs::PointCloud2& msg, const tf2_ros::Buffer& tf,
                       const std::string& base_frame, const std::string& sensor_frame,
                       const ::ros::Duration& tf_timeout,
                       const DepthCorrection* correction = nullptr);

/// Subscribes to a cloud topic and keeps the latest frames that converted (`keep` of them: the
/// frames a search fuses, ~frames). A cloud that does not convert is reported (throttled) and the
/// previous frames are kept.
class LatestFrame {
 public:
  LatestFrame(::ros::NodeHandle& nh, const std::string& topic, const tf2_ros::Buffer& tf,
              std::string base_frame, std::string sensor_frame,
              std::optional<DepthCorrection> correction = {}, std::size_t keep = 1);
  /// The latest frame, or null before the first one.
  std::shared_ptr<const Frame> get() const;
  /// The latest frame, waiting up to `seconds` for the first one (right after start-up it may
  /// still be on its way); null if none arrived by then. Needs the node to be spinning.
  std::shared_ptr<const Frame> wait(double seconds) const;
  /// The latest `count` frames (at most `keep`), oldest first, waiting up to `seconds` until that
  /// many have arrived; fewer if they did not by then, none if no frame did.
  std::vector<std::shared_ptr<const Frame>> wait_recent(std::size_t count, double seconds) const;
  /// The first frame stamped after `stamp` (a frame taken once the head settled, say), waiting
  /// up to `seconds`; null if none arrived by then.
  std::shared_ptr<const Frame> wait_newer(const ::ros::Time& stamp, double seconds) const;
  const std::string& topic() const { return topic_; }

 private:
  void receive(const sensor_msgs::PointCloud2ConstPtr& msg);
  /// Polls `ready` (under the lock) until it holds, `seconds` pass or ROS shuts down.
  template <class Ready>
  void wait_until(Ready&& ready, double seconds) const;

  const tf2_ros::Buffer& tf_;
  std::string topic_, base_frame_, sensor_frame_;
  std::optional<DepthCorrection> correction_;
  ::ros::Subscriber subscriber_;
  std::size_t keep_;
  mutable std::mutex mutex_;
  std::deque<std::shared_ptr<const Frame>> latest_;  ///< oldest first, at most keep_
};

}  // namespace lmk::ros1
