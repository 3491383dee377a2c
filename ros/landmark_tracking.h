// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// lmk_node's ~track (issue #48; docs/ros.md, "Tracking"): landmarks of the node's directory
// followed through every camera frame by the tracker (search/tracker.h), each frame moved into
// the base frame by TF as the searches' frames are. Per frame it publishes ~tracked (a stamped
// pose, confidence and state per landmark), a TF frame lmk/NAME per landmark in view, and RViz
// markers on ~tracked_markers. Tracking has its own callback queue and thread: following frames
// never waits behind a search the node is serving, nor a search behind it.

#include <lmk_msgs/Track.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>

#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/depth_correction.h"
#include "lmk/search/landmark_library.h"
#include "lmk/search/tracker.h"

namespace lmk::ros1 {

struct LandmarkTrackingSettings {
  std::string cloud_topic, base_frame, sensor_frame;
  TrackSettings track;  ///< find.scene.base_frame is always set: frames are in base_frame
  std::optional<DepthCorrection> depth_correction;
};

class LandmarkTracking {
 public:
  /// Advertises ~track, ~tracked and ~tracked_markers in `private_nh`'s namespace; follows
  /// nothing until ~track is called.
  LandmarkTracking(::ros::NodeHandle private_nh, LandmarkTrackingSettings settings,
                   const LandmarkLibrary& library, const tf2_ros::Buffer& tf);
  ~LandmarkTracking();

  bool track(lmk_msgs::Track::Request& request, lmk_msgs::Track::Response& response);

 private:
  void receive(const sensor_msgs::PointCloud2ConstPtr& msg);
  void publish(const std::vector<TrackedLandmark>& now, const std::string& frame_id,
               const ::ros::Time& stamp);

  LandmarkTrackingSettings settings_;
  const LandmarkLibrary& library_;
  const tf2_ros::Buffer& tf_;
  ::ros::CallbackQueue queue_;  ///< the camera's frames, served by spinner_ alone
  ::ros::NodeHandle frames_nh_;
  ::ros::AsyncSpinner spinner_;
  ::ros::Publisher tracked_, markers_;
  ::ros::ServiceServer service_;
  tf2_ros::TransformBroadcaster broadcaster_;
  std::mutex mutex_;
  ::ros::Subscriber cloud_;           ///< only while following
  std::unique_ptr<Tracker> tracker_;  ///< null: following nothing
  std::vector<std::string> names_;    ///< the landmarks followed, in the tracker's order
};

}  // namespace lmk::ros1
