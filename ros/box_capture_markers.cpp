// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/ros/box_capture_markers.h"

#include <algorithm>

#include "lmk/geometry/error.h"
#include "lmk/ros/geometry_conversion.h"

namespace lmk::ros1 {
namespace {

using visualization_msgs::InteractiveMarker;
using visualization_msgs::InteractiveMarkerControl;
using visualization_msgs::InteractiveMarkerFeedback;
using visualization_msgs::Marker;

const char* const kBox = "box";
const char* const kAxes = "xyz";

/// A control moving or turning about one axis of the marker's frame.
InteractiveMarkerControl axis_control(int axis, std::uint8_t mode, const std::string& name) {
  InteractiveMarkerControl c;
  c.name = name;
  c.interaction_mode = mode;
  // The control's orientation is the axis: +x, +y or +z of the marker.
  c.orientation.w = 1.0;
  if (axis == 1) c.orientation.z = 1.0;
  if (axis == 2) c.orientation.y = 1.0;
  const double norm =
      std::sqrt(c.orientation.w * c.orientation.w + c.orientation.y * c.orientation.y +
                c.orientation.z * c.orientation.z);
  c.orientation.w /= norm;
  c.orientation.y /= norm;
  c.orientation.z /= norm;
  return c;
}

std::string handle_name(int axis, int side) {
  return std::string("handle_") + (side > 0 ? "+" : "-") + kAxes[axis];
}

}  // namespace

Box move_box_face(const Box& box, int axis, int side, double offset, double min_side) {
  if (axis < 0 || axis > 2 || (side != 1 && side != -1)) throw Error("move_box_face: bad face");
  const double fixed = -side * 0.5 * box.size[axis];  // the opposite face, from the centre
  double moved = offset;
  // The moved face stays on its side of the fixed one, at least min_side away.
  if (side > 0) moved = std::max(moved, fixed + min_side);
  if (side < 0) moved = std::min(moved, fixed - min_side);
  Box out = box;
  out.size[axis] = std::abs(moved - fixed);
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();
  shift[axis] = 0.5 * (moved + fixed);
  out.pose.translation() = box.pose * shift;
  return out;
}

BoxCaptureMarkers::BoxCaptureMarkers(::ros::NodeHandle nh, const std::string& server_name,
                                     const std::string& base_frame,
                                     const std::string& capture_label, Actions actions,
                                     const Box& initial)
    : base_frame_(base_frame),
      actions_(std::move(actions)),
      box_(initial),
      server_(nh.resolveName(server_name), "", false) {
  // Entry ids follow insertion: 1 capture, 2 capture anyway, 3 find, 4 add this view, 5 forget
  // the added views (tests/ros select by id).
  menu_.insert("Capture as '" + capture_label + "'", [this](const auto&) {
    if (actions_.capture) actions_.capture(box(), false);
  });
  menu_.insert("Capture as '" + capture_label + "' even if not distinctive", [this](const auto&) {
    if (actions_.capture) actions_.capture(box(), true);
  });
  menu_.insert("Find this here", [this](const auto&) {
    if (actions_.find) actions_.find(box());
  });
  menu_.insert("Add this view", [this](const auto&) {
    if (actions_.add_view) actions_.add_view(false);
  });
  menu_.insert("Forget the added views", [this](const auto&) {
    if (actions_.add_view) actions_.add_view(true);
  });
  clicked_ = nh.subscribe("/clicked_point", 1, &BoxCaptureMarkers::on_clicked, this);
  publish();
}

Box BoxCaptureMarkers::box() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return box_;
}

void BoxCaptureMarkers::set_box(const Box& box) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    box_ = box;
  }
  publish();
}

// The box marker (move and turn on each axis, the menu on a click) and one handle per face.
void BoxCaptureMarkers::publish() {
  const Box box = this->box();
  InteractiveMarker marker;
  marker.header.frame_id = base_frame_;
  marker.name = kBox;
  marker.description = "landmark box";
  marker.pose = to_ros(box.pose);
  marker.scale = static_cast<float>(std::max(0.1, box.size.maxCoeff() * 1.2));
  InteractiveMarkerControl body;
  body.always_visible = true;
  body.interaction_mode = InteractiveMarkerControl::MENU;
  body.markers.push_back(box_marker(box, base_frame_, "lmk_capture", 0));
  body.markers.back().pose = geometry_msgs::Pose();
  body.markers.back().pose.orientation.w = 1.0;
  marker.controls.push_back(body);
  for (int axis = 0; axis < 3; ++axis) {
    marker.controls.push_back(axis_control(axis, InteractiveMarkerControl::MOVE_AXIS,
                                           std::string("move_") + kAxes[axis]));
    marker.controls.push_back(axis_control(axis, InteractiveMarkerControl::ROTATE_AXIS,
                                           std::string("rotate_") + kAxes[axis]));
  }
  server_.insert(marker, [this](const auto& f) { on_box(f); });
  menu_.apply(server_, kBox);

  for (int axis = 0; axis < 3; ++axis) {
    for (int side : {-1, 1}) {
      InteractiveMarker handle;
      handle.header.frame_id = base_frame_;
      handle.name = handle_name(axis, side);
      Eigen::Vector3d offset = Eigen::Vector3d::Zero();
      offset[axis] = side * 0.5 * box.size[axis];
      Eigen::Isometry3d T = box.pose;
      T.translation() = box.pose * offset;
      handle.pose = to_ros(T);
      handle.scale = 0.06f;
      InteractiveMarkerControl drag =
          axis_control(axis, InteractiveMarkerControl::MOVE_AXIS, "resize");
      drag.always_visible = true;
      Marker knob;
      knob.type = Marker::SPHERE;
      knob.scale.x = knob.scale.y = knob.scale.z = 0.015;
      knob.color.r = 1.0f;
      knob.color.g = 0.8f;
      knob.color.a = 1.0f;
      knob.pose.orientation.w = 1.0;
      drag.markers.push_back(knob);
      handle.controls.push_back(drag);
      server_.insert(handle, [this, axis, side](const auto& f) { on_handle(axis, side, f); });
    }
  }
  server_.applyChanges();
}

void BoxCaptureMarkers::on_box(const InteractiveMarkerFeedback::ConstPtr& feedback) {
  if (feedback->event_type != InteractiveMarkerFeedback::POSE_UPDATE &&
      feedback->event_type != InteractiveMarkerFeedback::MOUSE_UP)
    return;
  try {
    Box box = this->box();
    box.pose = from_ros(feedback->pose, "the dragged box");
    const std::lock_guard<std::mutex> lock(mutex_);
    box_ = box;
  } catch (const Error& e) {
    ROS_WARN("lmk: %s", e.what());
    return;
  }
  // Drag events come fast: the handles follow when the mouse is released.
  if (feedback->event_type == InteractiveMarkerFeedback::MOUSE_UP) publish();
}

void BoxCaptureMarkers::on_handle(int axis, int side,
                                  const InteractiveMarkerFeedback::ConstPtr& feedback) {
  if (feedback->event_type != InteractiveMarkerFeedback::POSE_UPDATE &&
      feedback->event_type != InteractiveMarkerFeedback::MOUSE_UP)
    return;
  const Box box = this->box();
  // Where the handle was dragged, along its axis from the box centre.
  const Eigen::Vector3d at(feedback->pose.position.x, feedback->pose.position.y,
                           feedback->pose.position.z);
  const double offset = (box.pose.inverse() * at)[axis];
  set_box(move_box_face(box, axis, side, offset));
}

void BoxCaptureMarkers::on_clicked(const geometry_msgs::PointStampedConstPtr& point) {
  if (!actions_.guess) return;
  try {
    set_box(actions_.guess(point->header.frame_id,
                           Eigen::Vector3d(point->point.x, point->point.y, point->point.z)));
    ROS_INFO("lmk: box guessed around the clicked point; adjust it, then capture it");
  } catch (const Error& e) {
    ROS_WARN("lmk: no box guess: %s", e.what());
  }
}

}  // namespace lmk::ros1
