// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Capture in RViz, as the paper's users did (docs/ros.md, "Capture in RViz"): an interactive-marker
// box in the base frame that the user drags and turns, and resizes with a handle on each face. A
// point published with RViz's "Publish Point" tool (/clicked_point) places a first guess of the
// box around the object under it (landmark/box_guess.h). The box's menu offers "Capture as
// '<~capture_name>'", the same "even if not distinctive", "Find this here", and "Add this view"
// and "Forget the added views": turn the head, add the frame, and the capture fuses every view.

#include <geometry_msgs/PointStamped.h>
#include <interactive_markers/interactive_marker_server.h>
#include <interactive_markers/menu_handler.h>
#include <ros/ros.h>

#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include "lmk/geometry/box.h"

namespace lmk::ros1 {

/// The box with the face (axis 0-2, side +1 or -1) moved to `offset` along that axis from the
/// box's centre, the opposite face staying put; no side gets shorter than `min_side`.
Box move_box_face(const Box& box, int axis, int side, double offset, double min_side = 0.01);

class BoxCaptureMarkers {
 public:
  struct Actions {
    /// Turns a clicked point (in the named frame) into a box in the base frame, or throws
    /// lmk::Error saying why not.
    std::function<Box(const std::string& frame, const Eigen::Vector3d&)> guess;
    /// "Capture as ..." (false) and "... even if not distinctive" (true).
    std::function<void(const Box&, bool force)> capture;
    std::function<void(const Box&)> find;  ///< "Find this here"
    /// "Add this view" (false) and "Forget the added views" (true): the next capture fuses the
    /// frames kept so far after its own (issue #35).
    std::function<void(bool clear)> add_view;
  };

  /// Serves the markers as `server_name` under `nh`; the box starts at `initial` in `base_frame`.
  BoxCaptureMarkers(::ros::NodeHandle nh, const std::string& server_name,
                    const std::string& base_frame, const std::string& capture_label,
                    Actions actions, const Box& initial);

  Box box() const;
  /// Moves the box (and its handles) to `box`.
  void set_box(const Box& box);

 private:
  void publish();
  void on_box(const visualization_msgs::InteractiveMarkerFeedbackConstPtr& feedback);
  void on_handle(int axis, int side,
                 const visualization_msgs::InteractiveMarkerFeedbackConstPtr& feedback);
  void on_clicked(const geometry_msgs::PointStampedConstPtr& point);

  std::string base_frame_;
  Actions actions_;
  mutable std::mutex mutex_;
  Box box_;
  interactive_markers::InteractiveMarkerServer server_;
  interactive_markers::MenuHandler menu_;
  ::ros::Subscriber clicked_;
};

}  // namespace lmk::ros1
