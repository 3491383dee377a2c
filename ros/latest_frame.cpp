// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/ros/latest_frame.h"

#include <algorithm>

#include "lmk/geometry/error.h"
#include "lmk/ros/cloud_conversion.h"
#include "lmk/ros/tf_lookup.h"

namespace lmk::ros1 {

Frame frame_from_cloud(const sensor_msgs::PointCloud2& msg, const tf2_ros::Buffer& tf,
                       const std::string& base_frame, const std::string& sensor_frame,
                       const ::ros::Duration& tf_timeout, const DepthCorrection* correction) {
  const std::string cloud_frame = msg.header.frame_id;
  if (cloud_frame.empty()) throw Error("the cloud has no frame_id");
  PointCloud cloud = from_ros(msg, "cloud in '" + cloud_frame + "'");
  if (!sensor_frame.empty() && sensor_frame != cloud_frame) {
    cloud.T_cloud_sensor = lookup_pose(tf, cloud_frame, sensor_frame, msg.header.stamp, tf_timeout);
  }
  if (correction) correction->apply(cloud);
  const Eigen::Isometry3d T_base_cloud =
      lookup_pose(tf, base_frame, cloud_frame, msg.header.stamp, tf_timeout);
  return Frame{cloud.transformed(T_base_cloud), base_frame, cloud_frame, msg.header.stamp};
}

LatestFrame::LatestFrame(::ros::NodeHandle& nh, const std::string& topic, const tf2_ros::Buffer& tf,
                         std::string base_frame, std::string sensor_frame,
                         std::optional<DepthCorrection> correction, std::size_t keep)
    : tf_(tf),
      topic_(topic),
      base_frame_(std::move(base_frame)),
      sensor_frame_(std::move(sensor_frame)),
      correction_(std::move(correction)),
      keep_(std::max<std::size_t>(keep, 1)) {
  // Queue of one: a search wants the newest frames, never a backlog.
  subscriber_ = nh.subscribe(topic, 1, &LatestFrame::receive, this);
}

template <class Ready>
void LatestFrame::wait_until(Ready&& ready, double seconds) const {
  const ::ros::WallTime deadline = ::ros::WallTime::now() + ::ros::WallDuration(seconds);
  while (true) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (ready()) return;
    }
    if (::ros::WallTime::now() >= deadline || !::ros::ok()) return;
    ::ros::WallDuration(0.02).sleep();
  }
}

std::shared_ptr<const Frame> LatestFrame::get() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return latest_.empty() ? nullptr : latest_.back();
}

std::shared_ptr<const Frame> LatestFrame::wait(double seconds) const {
  wait_until([&] { return !latest_.empty(); }, seconds);
  return get();
}

std::vector<std::shared_ptr<const Frame>> LatestFrame::wait_recent(std::size_t count,
                                                                   double seconds) const {
  count = std::min(count, keep_);
  wait_until([&] { return latest_.size() >= count; }, seconds);
  const std::lock_guard<std::mutex> lock(mutex_);
  const std::size_t n = std::min(count, latest_.size());
  return {latest_.end() - static_cast<std::ptrdiff_t>(n), latest_.end()};
}

std::shared_ptr<const Frame> LatestFrame::wait_newer(const ::ros::Time& stamp,
                                                     double seconds) const {
  wait_until([&] { return !latest_.empty() && latest_.back()->stamp > stamp; }, seconds);
  const std::shared_ptr<const Frame> frame = get();
  return frame && frame->stamp > stamp ? frame : nullptr;
}

void LatestFrame::receive(const sensor_msgs::PointCloud2ConstPtr& msg) {
  try {
    auto frame = std::make_shared<const Frame>(
        frame_from_cloud(*msg, tf_, base_frame_, sensor_frame_, ::ros::Duration(0.5),
                         correction_ ? &*correction_ : nullptr));
    const std::lock_guard<std::mutex> lock(mutex_);
    latest_.push_back(std::move(frame));
    if (latest_.size() > keep_) latest_.pop_front();
  } catch (const Error& e) {
    ROS_WARN_THROTTLE(5.0, "lmk: frame on %s dropped: %s", topic_.c_str(), e.what());
  }
}

}  // namespace lmk::ros1
