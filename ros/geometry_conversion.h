// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Poses, boxes and matches as ROS messages (docs/ros.md, "Conversions"): geometry_msgs for poses,
// visualization_msgs for what RViz draws, lmk_msgs for what the node's services return.

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Vector3.h>
#include <lmk_msgs/ErrorTerms.h>
#include <lmk_msgs/LandmarkMatch.h>
#include <lmk_msgs/MatchConfidence.h>
#include <visualization_msgs/Marker.h>
#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/search/find_landmark.h"
#include "lmk/search/metrics/error_metrics.h"

namespace lmk::ros1 {

geometry_msgs::Pose to_ros(const Eigen::Isometry3d& T);
geometry_msgs::Vector3 to_ros(const Eigen::Vector3d& v);
/// Throws lmk::Error naming `what` if the quaternion is not unit length within 1e-3 or a number is
/// not finite: a pose from the wire is checked before the robot acts on it.
Eigen::Isometry3d from_ros(const geometry_msgs::Pose& pose, const std::string& what);
Eigen::Vector3d from_ros(const geometry_msgs::Vector3& v);

lmk_msgs::ErrorTerms to_ros(const ErrorTerms& terms);
lmk_msgs::MatchConfidence to_ros(const MatchConfidence& confidence);
/// One match of the landmark `name`, ranked `rank` (1 for the best).
lmk_msgs::LandmarkMatch to_ros(const Match& match, const std::string& name, std::uint32_t rank);

/// A translucent CUBE over the box, in `frame_id`.
visualization_msgs::Marker box_marker(const Box& box, const std::string& frame_id,
                                      const std::string& ns, int id);

/// What the node publishes after a search: a DELETEALL (so that the last search's boxes go), then
/// per match a box coloured by its confidence (red through yellow to green as it rises from 0 to
/// 1; without one, the best of each landmark green and the others orange) and a label with the
/// landmark, rank, error (as `metric`, the search's, shows it) and confidence. Markers carry the
/// stamp 0, so that RViz draws them with the latest TF.
visualization_msgs::MarkerArray match_markers(const std::vector<lmk_msgs::LandmarkMatch>& matches,
                                              const std::string& frame_id,
                                              const ErrorMetric& metric);

}  // namespace lmk::ros1
