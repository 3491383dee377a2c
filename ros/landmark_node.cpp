// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/ros/landmark_node.h"

#include <visualization_msgs/MarkerArray.h>

#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "lmk/geometry/error.h"
#include "lmk/landmark/box_guess.h"
#include "lmk/landmark/capture_views.h"
#include "lmk/landmark/depth_correction_file.h"
#include "lmk/landmark/slide_check.h"
#include "lmk/occupancy/tsdf_volume.h"
#include "lmk/ros/geometry_conversion.h"
#include "lmk/ros/tf_lookup.h"
#include "lmk/search/capture_check.h"
#include "lmk/search/confidence/confidence_calibration.h"
#include "lmk/search/find_landmark.h"
#include "lmk/search/internal/find_settings_json.h"
#include "lmk/search/scene_index.h"

namespace lmk::ros1 {
namespace {

std::string default_landmark_directory() {
  const char* ros_home = std::getenv("ROS_HOME");
  const char* home = std::getenv("HOME");
  const std::string base = ros_home ? ros_home : std::string(home ? home : ".") + "/.ros";
  return base + "/lmk/landmarks";
}

std::string describe(const Eigen::Vector3d& p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.3f, %.3f, %.3f)", p.x(), p.y(), p.z());
  return text;
}

}  // namespace

LandmarkNodeSettings LandmarkNodeSettings::from_parameters(const ::ros::NodeHandle& private_nh) {
  LandmarkNodeSettings s;
  private_nh.param("cloud_topic", s.cloud_topic, s.cloud_topic);
  private_nh.param("base_frame", s.base_frame, s.base_frame);
  private_nh.param("sensor_frame", s.sensor_frame, s.sensor_frame);
  private_nh.param("landmark_directory", s.landmark_directory, default_landmark_directory());
  private_nh.param("frame_timeout", s.frame_timeout, s.frame_timeout);
  int frames = static_cast<int>(s.frames);
  private_nh.param("frames", frames, frames);
  if (frames < 1 || frames > static_cast<int>(kMaxFusedFrames)) {
    throw Error("~frames: must be 1 to " + std::to_string(kMaxFusedFrames) +
                " (frames fused per search)");
  }
  s.frames = static_cast<std::size_t>(frames);
  private_nh.param("interactive", s.interactive, s.interactive);
  private_nh.param("capture_name", s.capture_name, s.capture_name);
  LandmarkLibrary::check_name(s.capture_name);
  std::string depth_correction;
  private_nh.param("depth_correction", depth_correction, depth_correction);
  s.depth_correction = load_depth_correction_if_given(depth_correction);
  if (!(s.frame_timeout >= 0.0)) throw Error("~frame_timeout: must be seconds, 0 or more");
  // A string of JSON: a YAML map from rosparam would not read as one, and is refused rather than
  // silently ignored.
  std::string find_json = "{}";
  if (private_nh.hasParam("find_settings") && !private_nh.getParam("find_settings", find_json)) {
    throw Error(
        "~find_settings: must be a string of JSON, such as "
        "'{\"selection\": {\"threshold\": 0.006}}'");
  }
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(find_json);
  } catch (const nlohmann::json::exception& e) {
    throw Error("~find_settings: is not JSON (" + std::string(e.what()) + ")");
  }
  detail::find_settings_from_json(j, "~find_settings", s.find);
  // A team's own calibration (`lmk calibrate-confidence`), as `lmk find --calibration` takes it.
  std::string calibration;
  private_nh.param("confidence_calibration", calibration, calibration);
  if (!calibration.empty()) {
    s.find.selection.calibration =
        std::make_shared<const ConfidenceCalibration>(read_confidence_calibration(calibration));
  }
  if (s.base_frame.empty()) throw Error("~base_frame: must name a frame");
  return s;
}

LandmarkNode::LandmarkNode(::ros::NodeHandle nh, ::ros::NodeHandle private_nh,
                           LandmarkNodeSettings settings)
    : settings_(std::move(settings)),
      library_(settings_.landmark_directory),
      tf_listener_(tf_),
      latest_(nh, settings_.cloud_topic, tf_, settings_.base_frame, settings_.sensor_frame,
              settings_.depth_correction, settings_.frames) {
  // The node's scenes are in the base frame, whose +z is up (docs/landmarks.md, "Up").
  settings_.find.scene.base_frame = true;
  // Captures prepare their frame as the searches do (~find_settings' scene stage).
  prepare_capture_as_search(settings_.find.scene, settings_.capture);
  markers_ = private_nh.advertise<visualization_msgs::MarkerArray>("matches", 1, /*latch=*/true);
  capture_service_ = private_nh.advertiseService("capture_landmark", &LandmarkNode::capture, this);
  add_view_service_ = private_nh.advertiseService("add_view", &LandmarkNode::add_view, this);
  find_service_ = private_nh.advertiseService("find_landmark", &LandmarkNode::find, this);
  list_service_ = private_nh.advertiseService("list_landmarks", &LandmarkNode::list, this);
  LandmarkTrackingSettings tracking;
  tracking.cloud_topic = settings_.cloud_topic;
  tracking.base_frame = settings_.base_frame;
  tracking.sensor_frame = settings_.sensor_frame;
  tracking.track.find = settings_.find;
  tracking.depth_correction = settings_.depth_correction;
  tracking_ = std::make_unique<LandmarkTracking>(private_nh, std::move(tracking), library_, tf_);
  if (settings_.interactive) {
    BoxCaptureMarkers::Actions actions;
    actions.guess = [this](const std::string& f, const Eigen::Vector3d& p) {
      return guess_at(f, p);
    };
    actions.capture = [this](const Box& box, bool force) { capture_from_rviz(box, force); };
    actions.find = [this](const Box& box) { find_from_rviz(box); };
    actions.add_view = [this](bool clear) {
      try {
        ROS_INFO("lmk: %s", keep_view(clear).c_str());
      } catch (const Error& e) {
        ROS_WARN("lmk: add a view from RViz: %s", e.what());
      }
    };
    // The box starts 0.8 m ahead of the robot at table height, until a click places it.
    const Box initial(Eigen::Isometry3d(Eigen::Translation3d(0.8, 0.0, 0.8)),
                      Eigen::Vector3d(0.2, 0.2, 0.2));
    rviz_box_ = std::make_unique<BoxCaptureMarkers>(private_nh, "capture_box", settings_.base_frame,
                                                    settings_.capture_name, actions, initial);
  }
  ROS_INFO("lmk: landmarks in %s; frames from %s in %s", library_.directory().c_str(),
           settings_.cloud_topic.c_str(), settings_.base_frame.c_str());
}

Error LandmarkNode::no_frame() const {
  return Error("no frame from " + latest_.topic() + " yet (is the camera publishing, and does " +
               "TF reach " + settings_.base_frame + "?)");
}

std::shared_ptr<const Frame> LandmarkNode::frame() const {
  std::shared_ptr<const Frame> frame = latest_.wait(settings_.frame_timeout);
  if (!frame) throw no_frame();
  return frame;
}

std::shared_ptr<const Frame> LandmarkNode::search_frame(std::size_t& fused) const {
  if (settings_.frames == 1) {
    fused = 1;
    return frame();
  }
  const std::vector<std::shared_ptr<const Frame>> recent =
      latest_.wait_recent(settings_.frames, settings_.frame_timeout);
  if (recent.empty()) throw no_frame();  // wait_recent waited ~frame_timeout already
  fused = recent.size();
  if (fused == 1) return recent.front();
  // Every frame is in the base frame already, its sensor placed by TF at its own stamp.
  std::vector<DepthFrame> frames;
  for (const auto& f : recent) frames.push_back({&f->scene, Eigen::Isometry3d::Identity()});
  auto out = std::make_shared<Frame>(*recent.back());
  out->scene = fuse_frames(frames);
  return out;
}

// The service handlers answer every failure in the response (success = false and the reason),
// never by returning false: a false return reaches the caller as a bare "service call failed".
bool LandmarkNode::capture(lmk_msgs::CaptureLandmark::Request& request,
                           lmk_msgs::CaptureLandmark::Response& response) {
  try {
    LandmarkLibrary::check_name(request.name);
    if (!request.overwrite && library_.contains(request.name)) {
      throw Error("a landmark '" + request.name + "' exists already; set overwrite to replace it");
    }
    // The request is checked whole before anything waits for a frame.
    const Eigen::Isometry3d T_boxframe_box = from_ros(request.box_pose.pose, "box_pose");
    const Eigen::Vector3d box_size = from_ros(request.box_size);
    const std::string& box_frame = request.box_pose.header.frame_id.empty()
                                       ? settings_.base_frame
                                       : request.box_pose.header.frame_id;
    // The box itself before any wait: an infinite size got "no frame yet" (issue #34, finding 5).
    check_capture_box(Box(T_boxframe_box, box_size), settings_.capture, "capture_landmark");
    const Eigen::Isometry3d T_base_boxframe =
        lookup_pose(tf_, settings_.base_frame, box_frame, ::ros::Time(0), ::ros::Duration(0.5));
    capture_box(request.name, Box(T_base_boxframe * T_boxframe_box, box_size), request.force,
                request.overwrite, request.use_added_views, response);
  } catch (const Error& e) {
    response.success = false;
    response.message = e.what();
    ROS_WARN("lmk: capture_landmark: %s", e.what());
  }
  return true;
}

std::string LandmarkNode::keep_view(bool clear) {
  if (clear) {
    const std::lock_guard<std::mutex> lock(views_mutex_);
    added_views_.clear();
    return "forgot the added views";
  }
  std::shared_ptr<const Frame> frame = this->frame();
  const std::lock_guard<std::mutex> lock(views_mutex_);
  if (added_views_.size() + 1 >= kMaxLandmarkViews) {
    throw Error("already " + std::to_string(added_views_.size()) +
                " views kept: a landmark takes at most " + std::to_string(kMaxLandmarkViews) +
                " with the capture's own frame");
  }
  added_views_.push_back(std::move(frame));
  return "kept this frame as view " + std::to_string(added_views_.size() + 1) +
         " of the next capture that uses the added views";
}

bool LandmarkNode::add_view(lmk_msgs::AddView::Request& request,
                            lmk_msgs::AddView::Response& response) {
  try {
    response.message = keep_view(request.clear);
    response.success = true;
  } catch (const Error& e) {
    response.success = false;
    response.message = e.what();
  }
  const std::lock_guard<std::mutex> lock(views_mutex_);
  response.views = static_cast<std::uint32_t>(added_views_.size());
  return true;
}

void LandmarkNode::capture_box(const std::string& name, const Box& box, bool force, bool overwrite,
                               bool use_added_views,
                               lmk_msgs::CaptureLandmark::Response& response) {
  const std::shared_ptr<const Frame> frame = this->frame();
  response.header.frame_id = frame->base_frame;
  response.header.stamp = frame->stamp;
  std::vector<std::shared_ptr<const Frame>> added;
  if (use_added_views) {
    const std::lock_guard<std::mutex> lock(views_mutex_);
    added = added_views_;
    if (added.empty()) throw Error("no view added: call add_view (RViz: \"Add this view\") first");
  }
  std::vector<const PointCloud*> clouds{&frame->scene};
  for (const auto& view : added) clouds.push_back(&view->scene);
  // The frames share the base frame: each further view is registered onto the latest from there.
  std::string registered;
  const std::vector<CaptureView> views =
      place_views(clouds, box, ViewPlacement{}, [&](std::size_t view, const ViewRegistration& r) {
        char text[96];
        std::snprintf(text, sizeof(text), "; view %zu registered: overlap %.0f%%, residual %.1f mm",
                      view, 100.0 * r.overlap, 1000.0 * r.residual);
        registered += text;
      });
  Landmark landmark = capture_views(views, box, name, settings_.capture);
  response.views = static_cast<std::uint32_t>(landmark.view_count());

  // The capture check (search/capture_check.h), whose findings the file keeps.
  FindSettings check_settings = settings_.find;
  check_settings.scene.up = landmark.up;
  const CaptureCheck check = check_capture(landmark, &frame->scene, check_settings);
  landmark.findings = check.findings;
  response.found_itself = check.findings.found_itself;
  const std::vector<Match> none;
  const std::vector<Match>& others = check.look_alikes ? check.look_alikes->other_instances : none;
  for (std::size_t i = 0; i < others.size(); ++i) {
    response.other_instances.push_back(
        to_ros(others[i], landmark.name, static_cast<std::uint32_t>(i + 1)));
  }
  std::string verdict = check.findings.found_itself
                            ? ""
                            : "the search does not find it in its own frame (too few points or "
                              "too little shape); ";
  if (!others.empty()) {
    verdict += "it also matches " + std::to_string(others.size()) +
               " other place(s), the best at " + describe(others.front().box.center()) + "; ";
  }
  if (!verdict.empty() && !force) {
    response.success = false;
    response.message = "not written: " + verdict + "draw the box with more context or more " +
                       "empty margin, or set force to keep it anyway";
    return;
  }
  response.file = library_.save(landmark, overwrite).string();
  response.success = true;
  response.message =
      "wrote '" + landmark.name + "' (" + std::to_string(landmark.points.size()) + " points" +
      (landmark.multi_view() ? ", " + std::to_string(landmark.view_count()) + " views" : "") + ")" +
      (verdict.empty() ? "; distinctive in this frame" : "; kept despite: " + verdict) + registered;
  if (use_added_views) {  // written: the next landmark starts from its own views
    const std::lock_guard<std::mutex> lock(views_mutex_);
    added_views_.clear();
  }
  // The slide check (landmark/slide_check.h): advice shown with the result in RViz, not a refusal.
  for (const std::string& line : describe_slides(check.slides, landmark.box))
    response.message += "; " + line;
  ROS_INFO("lmk: %s", response.message.c_str());
}

Box LandmarkNode::guess_at(const std::string& frame_id, const Eigen::Vector3d& point) {
  const std::string& from = frame_id.empty() ? settings_.base_frame : frame_id;
  const Eigen::Isometry3d T_base_from =
      lookup_pose(tf_, settings_.base_frame, from, ::ros::Time(0), ::ros::Duration(0.5));
  return guess_box(frame()->scene, T_base_from * point).box;
}

void LandmarkNode::capture_from_rviz(const Box& box, bool force) {
  // The first free name of NAME, NAME-2, NAME-3, ...: a menu cannot ask for one.
  std::string name = settings_.capture_name;
  for (int n = 2; library_.contains(name); ++n) {
    name = settings_.capture_name + "-" + std::to_string(n);
  }
  lmk_msgs::CaptureLandmark::Response response;
  bool use_added_views = false;
  {
    const std::lock_guard<std::mutex> lock(views_mutex_);
    use_added_views = !added_views_.empty();
  }
  try {
    capture_box(name, box, force, false, use_added_views, response);
  } catch (const Error& e) {
    ROS_WARN("lmk: capture from RViz: %s", e.what());
    return;
  }
  if (!response.success) ROS_WARN("lmk: capture from RViz: %s", response.message.c_str());
  if (!response.other_instances.empty()) publish_matches(response.other_instances);
}

void LandmarkNode::find_from_rviz(const Box& box) {
  try {
    const std::shared_ptr<const Frame> frame = this->frame();
    const Landmark landmark = lmk::capture(frame->scene, box, "this", settings_.capture);
    const FindResult result = find_landmark(frame->scene, landmark, settings_.find);
    std::vector<lmk_msgs::LandmarkMatch> matches;
    for (std::size_t i = 0; i < result.matches.size(); ++i) {
      matches.push_back(to_ros(result.matches[i], "this", static_cast<std::uint32_t>(i + 1)));
    }
    publish_matches(matches);
    ROS_INFO("lmk: the box's contents match %zu place(s) in this frame", matches.size());
  } catch (const Error& e) {
    ROS_WARN("lmk: find from RViz: %s", e.what());
  }
}

void LandmarkNode::publish_matches(const std::vector<lmk_msgs::LandmarkMatch>& matches) {
  markers_.publish(match_markers(matches, settings_.base_frame,
                                 find_error_metric(settings_.find.resolved().selection.metric)));
}

bool LandmarkNode::find(lmk_msgs::FindLandmark::Request& request,
                        lmk_msgs::FindLandmark::Response& response) {
  try {
    const std::vector<std::string> names =
        request.name.empty() ? library_.names() : std::vector<std::string>{request.name};
    if (names.empty()) throw Error("no landmarks in " + library_.directory().string());
    for (const std::string& name : names) {  // the request before any wait for a frame
      LandmarkLibrary::check_name(name);
      if (!library_.contains(name)) {
        throw Error("no landmark '" + name + "' in " + library_.directory().string());
      }
    }
    std::size_t fused = 1;
    const std::shared_ptr<const Frame> frame = search_frame(fused);
    response.header.frame_id = frame->base_frame;
    response.header.stamp = frame->stamp;
    // One index of the frame for every landmark (steps 1-2 of the search).
    const SceneIndex index(frame->scene, settings_.find.scene);
    std::string summary;
    for (const std::string& name : names) {
      const FindResult result =
          find_landmark(index, *library_.index(name, settings_.find), settings_.find);
      for (std::size_t i = 0; i < result.matches.size(); ++i) {
        response.matches.push_back(
            to_ros(result.matches[i], name, static_cast<std::uint32_t>(i + 1)));
      }
      summary += (summary.empty() ? "" : "; ") + name + ": " +
                 std::to_string(result.matches.size()) + " match(es)";
    }
    response.success = true;
    response.message = fused > 1 ? std::to_string(fused) + " frames fused; " + summary : summary;
    publish_matches(response.matches);
  } catch (const Error& e) {
    response.success = false;
    response.message = e.what();
    ROS_WARN("lmk: find_landmark: %s", e.what());
  }
  return true;
}

bool LandmarkNode::list(lmk_msgs::ListLandmarks::Request&,
                        lmk_msgs::ListLandmarks::Response& response) {
  try {
    for (const std::string& name : library_.names()) {
      response.names.push_back(name);
      response.files.push_back(library_.path_of(name).string());
    }
  } catch (const Error& e) {
    ROS_WARN("lmk: list_landmarks: %s", e.what());
  }
  return true;
}

}  // namespace lmk::ros1
