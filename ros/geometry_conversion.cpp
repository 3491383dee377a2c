// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/ros/geometry_conversion.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lmk/geometry/pose.h"
#include "lmk/geometry/settings_schema.h"

namespace lmk::ros1 {

geometry_msgs::Pose to_ros(const Eigen::Isometry3d& T) {
  geometry_msgs::Pose pose;
  pose.position.x = T.translation().x();
  pose.position.y = T.translation().y();
  pose.position.z = T.translation().z();
  const Eigen::Quaterniond q(T.linear());
  pose.orientation.w = q.w();
  pose.orientation.x = q.x();
  pose.orientation.y = q.y();
  pose.orientation.z = q.z();
  return pose;
}

geometry_msgs::Vector3 to_ros(const Eigen::Vector3d& v) {
  geometry_msgs::Vector3 out;
  out.x = v.x();
  out.y = v.y();
  out.z = v.z();
  return out;
}

Eigen::Isometry3d from_ros(const geometry_msgs::Pose& pose, const std::string& what) {
  return pose_from_unit_quaternion(
      Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z),
      Eigen::Vector4d(pose.orientation.w, pose.orientation.x, pose.orientation.y,
                      pose.orientation.z),
      what, "orientation");
}

Eigen::Vector3d from_ros(const geometry_msgs::Vector3& v) { return {v.x, v.y, v.z}; }

lmk_msgs::ErrorTerms to_ros(const ErrorTerms& t) {
  lmk_msgs::ErrorTerms out;
  out.scene_to_landmark_sum = t.scene_to_landmark_sum;
  out.scene_to_landmark_count = t.scene_to_landmark_count;
  out.landmark_to_scene_sum = t.landmark_to_scene_sum;
  out.landmark_to_scene_count = t.landmark_to_scene_count;
  out.scene_points_in_box = t.scene_points_in_box;
  // The message has every term: those the metric did not measure as they always were (NaN
  // coverage and observed share, zero counts).
  const SupportTerms support = t.support.value_or(SupportTerms{});
  const EmptySpaceTerms empty = t.empty_space.value_or(EmptySpaceTerms{});
  out.coverage = t.coverage();
  out.empty_space_probes = empty.probes;
  out.empty_space_violations = empty.violations;
  out.empty_space_violation_mean = empty.violation_mean;
  out.unseen_points = support.unseen_points;
  out.seen_through_points = support.seen_through_points;
  out.empty_space_observed = empty.observed;
  out.range_scale = t.range_scale;
  return out;
}

lmk_msgs::LandmarkMatch to_ros(const Match& match, const std::string& name, std::uint32_t rank) {
  lmk_msgs::LandmarkMatch out;
  out.landmark = name;
  out.rank = rank;
  out.pose = to_ros(match.T_scene_capture);
  out.box_pose = to_ros(match.box.pose);
  out.box_size = to_ros(match.box.size);
  out.error = match.error;
  out.terms = to_ros(match.terms);
  out.confidence = to_ros(match.confidence);
  return out;
}

lmk_msgs::MatchConfidence to_ros(const MatchConfidence& c) {
  lmk_msgs::MatchConfidence out;
  out.probability = c.probability;
  out.margin = c.margin;
  out.error_sigma = c.error_sigma;
  out.range = c.range;
  out.support = c.support;
  out.freedom = c.freedom;
  out.coverage = c.coverage;
  out.intrusion = c.intrusion;
  out.free_space_seen = c.free_space_seen;
  out.competitor_kind = setting_name(c.competitor.kind);
  out.competitor_box_pose = to_ros(c.competitor.box.pose);
  out.competitor_error = c.competitor.error;
  out.competitor_distance = c.competitor.distance;
  out.competitor_angle = c.competitor.angle;
  out.doubt = c.doubt;
  return out;
}

namespace {

std_msgs::ColorRGBA rgba(float r, float g, float b, float a) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

visualization_msgs::Marker marker(const std::string& frame_id, const std::string& ns, int id,
                                  int type) {
  visualization_msgs::Marker m;
  m.header.frame_id = frame_id;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  return m;
}

// Red at 0, yellow at a half, green at 1: how sure a match is, at a glance.
std_msgs::ColorRGBA confidence_colour(double probability, float alpha) {
  const float p = static_cast<float>(std::clamp(probability, 0.0, 1.0));
  return rgba(std::min(1.0f, 2.0f * (1.0f - p)), std::min(1.0f, 2.0f * p), 0.1f, alpha);
}

}  // namespace

visualization_msgs::Marker box_marker(const Box& box, const std::string& frame_id,
                                      const std::string& ns, int id) {
  visualization_msgs::Marker m = marker(frame_id, ns, id, visualization_msgs::Marker::CUBE);
  m.pose = to_ros(box.pose);
  m.scale = to_ros(box.size);
  m.color = rgba(0.2f, 0.6f, 1.0f, 0.35f);
  return m;
}

visualization_msgs::MarkerArray match_markers(const std::vector<lmk_msgs::LandmarkMatch>& matches,
                                              const std::string& frame_id,
                                              const ErrorMetric& metric) {
  visualization_msgs::MarkerArray array;
  visualization_msgs::Marker clear;
  clear.action = visualization_msgs::Marker::DELETEALL;
  array.markers.push_back(clear);
  int id = 0;
  for (const lmk_msgs::LandmarkMatch& match : matches) {
    visualization_msgs::Marker box =
        marker(frame_id, "lmk_matches", id++, visualization_msgs::Marker::CUBE);
    box.pose = match.box_pose;
    box.scale = match.box_size;
    const float alpha = match.rank == 1 ? 0.45f : 0.3f;
    const double p = match.confidence.probability;
    if (std::isfinite(p)) {
      box.color = confidence_colour(p, alpha);
    } else {
      box.color = match.rank == 1 ? rgba(0.1f, 0.8f, 0.2f, alpha) : rgba(1.0f, 0.55f, 0.0f, alpha);
    }
    array.markers.push_back(box);

    visualization_msgs::Marker label =
        marker(frame_id, "lmk_labels", id++, visualization_msgs::Marker::TEXT_VIEW_FACING);
    label.pose.position = match.box_pose.position;
    label.pose.position.z += 0.5 * match.box_size.z + 0.04;
    label.scale.z = 0.04;  // text height, m
    label.color = rgba(1.0f, 1.0f, 1.0f, 1.0f);
    char text[200];
    std::snprintf(text, sizeof text, "%s #%u  %s", match.landmark.c_str(), match.rank,
                  format_error(match.error, metric).c_str());
    label.text = text;
    if (std::isfinite(p)) {
      std::snprintf(text, sizeof text, "  confidence %.2f", p);
      label.text += text;
    }
    array.markers.push_back(label);
  }
  return array;
}

}  // namespace lmk::ros1
