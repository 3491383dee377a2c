// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// lmk_node's work (docs/ros.md, "lmk_node"): keeps the latest camera frame in the base frame and
// serves capture_landmark, add_view, find_landmark and list_landmarks over a landmark directory,
// publishing the last search's matches as a latched MarkerArray for RViz; and ~track, landmarks
// followed in every frame (landmark_tracking.h).

#include <lmk_msgs/AddView.h>
#include <lmk_msgs/CaptureLandmark.h>
#include <lmk_msgs/FindLandmark.h>
#include <lmk_msgs/ListLandmarks.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "lmk/geometry/error.h"
#include "lmk/landmark/landmark.h"
#include "lmk/ros/box_capture_markers.h"
#include "lmk/ros/landmark_tracking.h"
#include "lmk/ros/latest_frame.h"
#include "lmk/search/find_settings.h"
#include "lmk/search/landmark_library.h"

namespace lmk::ros1 {

struct LandmarkNodeSettings {
  std::string cloud_topic = "/head_mount_kinect/depth_registered/points";  ///< the PR2 head Kinect
  std::string base_frame = "base_link";
  std::string sensor_frame;        ///< the camera's optical frame; empty: the cloud's frame
  std::string landmark_directory;  ///< where NAME.lmk files live
  double frame_timeout = 3.0;      ///< s a service waits for the first frame(s)
  /// Frames a search fuses (occupancy/tsdf_volume.h): the latest `frames`, each placed by TF at
  /// its stamp, so the head may move between them. 1: the latest frame alone, as before.
  std::size_t frames = 1;
  FindSettings find;        ///< scene.base_frame is always set: scenes are in base_frame
  bool interactive = true;  ///< serve the RViz capture box (box_capture_markers.h)
  std::string capture_name = "landmark";  ///< RViz captures are NAME, NAME-2, NAME-3, ...
  CaptureSettings capture;                ///< base_frame is always set likewise
  /// The camera's depth error (a file of lmk calibrate-depth, ~depth_correction), undone on every
  /// frame before capture and search alike.
  std::optional<DepthCorrection> depth_correction;

  /// From the private parameters ~cloud_topic, ~base_frame, ~sensor_frame,
  /// ~landmark_directory (default $ROS_HOME/lmk/landmarks), ~frame_timeout, ~frames, ~interactive,
  /// ~capture_name, ~depth_correction (a file) and ~find_settings (FindSettings as JSON, one object
  /// per stage, e.g. {"selection": {"threshold": 0.006}}; search/internal/find_settings_json.h).
  /// Throws lmk::Error for a bad one.
  static LandmarkNodeSettings from_parameters(const ::ros::NodeHandle& private_nh);
};

class LandmarkNode {
 public:
  /// Advertises the services and the marker topic in `private_nh`'s namespace.
  LandmarkNode(::ros::NodeHandle nh, ::ros::NodeHandle private_nh, LandmarkNodeSettings settings);

  bool capture(lmk_msgs::CaptureLandmark::Request& request,
               lmk_msgs::CaptureLandmark::Response& response);
  /// Keeps the latest frame as a further view of the next capture that fuses views (issue #35).
  bool add_view(lmk_msgs::AddView::Request& request, lmk_msgs::AddView::Response& response);
  bool find(lmk_msgs::FindLandmark::Request& request, lmk_msgs::FindLandmark::Response& response);
  bool list(lmk_msgs::ListLandmarks::Request& request, lmk_msgs::ListLandmarks::Response& response);

 private:
  /// The latest frame; lmk::Error when none has arrived yet.
  std::shared_ptr<const Frame> frame() const;
  /// The error of a service that waited for a frame in vain.
  Error no_frame() const;
  /// What a search runs on: the latest frame, or the latest ~frames fused into one (fewer when
  /// fewer arrived within ~frame_timeout of start-up), stamped as the newest. `fused` says how
  /// many frames it holds. lmk::Error when none has arrived yet.
  std::shared_ptr<const Frame> search_frame(std::size_t& fused) const;
  /// Captures `box` (base frame) from the latest frame, and with `use_added_views` the kept views
  /// after it (registered onto it as `lmk capture A B` registers, place_views), as `name` into the
  /// library, unless the distinctiveness check objects and `force` is off; fills the response
  /// either way. A landmark written from the kept views forgets them.
  void capture_box(const std::string& name, const Box& box, bool force, bool overwrite,
                   bool use_added_views, lmk_msgs::CaptureLandmark::Response& response);
  /// Keeps the latest frame as a view, or forgets the kept ones; says what it did.
  std::string keep_view(bool clear);
  /// The RViz menu's actions.
  Box guess_at(const std::string& frame_id, const Eigen::Vector3d& point);
  void capture_from_rviz(const Box& box, bool force);
  void find_from_rviz(const Box& box);
  void publish_matches(const std::vector<lmk_msgs::LandmarkMatch>& matches);

  LandmarkNodeSettings settings_;
  LandmarkLibrary library_;
  tf2_ros::Buffer tf_;
  tf2_ros::TransformListener tf_listener_;
  LatestFrame latest_;
  ::ros::Publisher markers_;
  ::ros::ServiceServer capture_service_, add_view_service_, find_service_, list_service_;
  mutable std::mutex views_mutex_;
  std::vector<std::shared_ptr<const Frame>> added_views_;  ///< views kept for the next capture
  std::unique_ptr<BoxCaptureMarkers> rviz_box_;
  std::unique_ptr<LandmarkTracking> tracking_;  ///< ~track (issue #48)
};

}  // namespace lmk::ros1
