// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/ros/landmark_tracking.h"

#include <geometry_msgs/TransformStamped.h>
#include <lmk_msgs/TrackedLandmarks.h>
#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/MarkerArray.h>

#include <cmath>
#include <limits>

#include "lmk/geometry/error.h"
#include "lmk/ros/geometry_conversion.h"
#include "lmk/ros/latest_frame.h"

namespace lmk::ros1 {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

lmk_msgs::TrackedLandmark to_ros(const TrackedLandmark& t) {
  lmk_msgs::TrackedLandmark m;
  m.name = t.name;
  m.state = to_string(t.state);
  m.error = t.match ? t.match->error : kNaN;
  m.confidence = t.match ? t.match->confidence.probability : kNaN;
  m.lost_because = to_string(t.lost_because);
  m.seconds = t.seconds;
  if (t.match) {
    m.box_pose = lmk::ros1::to_ros(t.match->box.pose);
    m.box_size = lmk::ros1::to_ros(t.match->box.size);
  } else {
    m.box_pose.orientation.w = 1.0;
  }
  return m;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "'" : ", '") + n + "'";
  return out;
}

}  // namespace

LandmarkTracking::LandmarkTracking(::ros::NodeHandle private_nh, LandmarkTrackingSettings settings,
                                   const LandmarkLibrary& library, const tf2_ros::Buffer& tf)
    : settings_(std::move(settings)),
      library_(library),
      tf_(tf),
      frames_nh_(private_nh),
      spinner_(1, &queue_) {
  settings_.track.find.scene.base_frame = true;
  frames_nh_.setCallbackQueue(&queue_);
  tracked_ = private_nh.advertise<lmk_msgs::TrackedLandmarks>("tracked", 10);
  markers_ = private_nh.advertise<visualization_msgs::MarkerArray>("tracked_markers", 1, true);
  service_ = private_nh.advertiseService("track", &LandmarkTracking::track, this);
  spinner_.start();
}

LandmarkTracking::~LandmarkTracking() {
  spinner_.stop();
  cloud_.shutdown();
}

bool LandmarkTracking::track(lmk_msgs::Track::Request& request,
                             lmk_msgs::Track::Response& response) {
  try {
    if (request.stop) {
      const std::lock_guard<std::mutex> lock(mutex_);
      cloud_.shutdown();
      tracker_.reset();
      response.message =
          names_.empty() ? "was following nothing" : "stopped following " + joined(names_);
      names_.clear();
      markers_.publish(
          match_markers({}, settings_.base_frame,
                        find_error_metric(settings_.track.find.resolved().selection.metric)));
      response.success = true;
      return true;
    }
    std::vector<std::string> names =
        request.landmarks.empty() ? library_.names() : request.landmarks;
    if (names.empty()) throw Error("no landmarks in " + library_.directory().string());
    std::vector<std::shared_ptr<const Landmark>> landmarks;
    for (const std::string& name : names) landmarks.push_back(library_.load(name));
    auto tracker = std::make_unique<Tracker>(std::move(landmarks), settings_.track);
    const std::lock_guard<std::mutex> lock(mutex_);
    tracker_ = std::move(tracker);  // a new request starts afresh: every landmark searched first
    names_ = names;
    if (!cloud_) {
      cloud_ = frames_nh_.subscribe(settings_.cloud_topic, 1, &LandmarkTracking::receive, this);
    }
    response.success = true;
    response.landmarks = names_;
    response.message = "following " + joined(names_) + " in every frame of " +
                       settings_.cloud_topic + ", in " + settings_.base_frame;
  } catch (const Error& e) {
    response.success = false;
    response.message = e.what();
  }
  return true;
}

void LandmarkTracking::receive(const sensor_msgs::PointCloud2ConstPtr& msg) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!tracker_) return;
  try {
    const Frame frame = frame_from_cloud(
        *msg, tf_, settings_.base_frame, settings_.sensor_frame, ::ros::Duration(0.2),
        settings_.depth_correction ? &*settings_.depth_correction : nullptr);
    publish(tracker_->update(frame.scene), frame.base_frame, frame.stamp);
  } catch (const Error& e) {
    ROS_WARN_THROTTLE(5.0, "lmk: track: a frame was skipped: %s", e.what());
  }
}

void LandmarkTracking::publish(const std::vector<TrackedLandmark>& now, const std::string& frame_id,
                               const ::ros::Time& stamp) {
  lmk_msgs::TrackedLandmarks out;
  out.header.frame_id = frame_id;
  out.header.stamp = stamp;
  visualization_msgs::MarkerArray markers;
  int id = 0;
  for (const TrackedLandmark& t : now) {
    out.landmarks.push_back(to_ros(t));
    if (!t.match) {
      visualization_msgs::Marker gone;
      gone.header = out.header;
      gone.ns = "lmk_tracked";
      gone.id = id++;
      gone.action = visualization_msgs::Marker::DELETE;
      markers.markers.push_back(gone);
      continue;
    }
    // A TF frame per landmark in view: a robot's code can look up lmk/NAME like any link.
    geometry_msgs::TransformStamped T = tf2::eigenToTransform(t.match->box.pose);
    T.header = out.header;
    T.child_frame_id = "lmk/" + t.name;
    broadcaster_.sendTransform(T);
    visualization_msgs::Marker box = box_marker(t.match->box, frame_id, "lmk_tracked", id++);
    box.header.stamp = stamp;
    markers.markers.push_back(box);
  }
  tracked_.publish(out);
  markers_.publish(markers);
}

}  // namespace lmk::ros1
