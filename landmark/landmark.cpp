// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/landmark.h"

#include <cmath>

#include "lmk/geometry/error.h"
#include "lmk/geometry/kdtree.h"
#include "lmk/geometry/normals.h"

namespace lmk {
namespace {

// A depth camera measures a few metres: a sensor origin farther than this from the landmark's box
// (a forged 1e300, issue #61) would put every ray's free space out of reach, and the landmark would
// find nothing without saying why. Relative to the box, so that a map's large coordinates pass.
constexpr double kMaxSensorDistance = 100.0;  // m

void check_sensor_distance(const Eigen::Vector3d& origin, const Box& box, const std::string& what) {
  const double distance = (origin - box.center()).norm();
  if (!(distance <= kMaxSensorDistance)) {
    throw Error(what + ": a sensor origin lies " + std::to_string(distance) +
                " m from the landmark's box; a depth camera sees within 100 m");
  }
}

}  // namespace

void Landmark::validate(const std::string& what) const {
  if (format_version != kLandmarkFormatVersion) {
    throw Error(what + ": landmark format version " + std::to_string(format_version) +
                " is not supported (this lmk reads version " +
                std::to_string(kLandmarkFormatVersion) + ")");
  }
  if (name.empty()) throw Error(what + ": landmark name is empty");
  // The name is printed by every command that shows the landmark: no control character may reach
  // a terminal through it (issue #47).
  if (!is_printable_text(name)) {
    throw Error(what + ": landmark name '" + printable(name, kEchoedBytes) +
                "' is not printable text (a control character or a byte that is not UTF-8)");
  }
  check_capture_settings(settings, what);
  check_capture_box(box, settings, what);
  if (!sensor_origin.allFinite()) throw Error(what + ": sensor origin is not finite");
  check_sensor_distance(sensor_origin, box, what);
  if (!up.allFinite() || std::abs(up.norm() - 1.0) > 1e-6) {
    throw Error(what + ": the up axis must be a finite unit vector");
  }
  validate_views(what);
  if (points.empty()) throw Error(what + ": landmark has no points");
  if (points.count_finite() != points.size()) {
    throw Error(what + ": landmark points must all be finite");
  }
  points.validate(what);
}

void Landmark::validate_views(const std::string& what) const {
  if (!multi_view()) {
    if (!point_views.empty()) throw Error(what + ": point views without the views");
    return;
  }
  if (view_origins.size() < 2 || view_origins.size() > kMaxLandmarkViews) {
    throw Error(what + ": a landmark of several views needs 2 to " +
                std::to_string(kMaxLandmarkViews) + " views, not " +
                std::to_string(view_origins.size()));
  }
  for (const Eigen::Vector3d& o : view_origins) {
    if (!o.allFinite()) throw Error(what + ": a view's sensor origin is not finite");
    check_sensor_distance(o, box, what);
  }
  if (view_origins.front() != sensor_origin) {
    throw Error(what + ": the first view's sensor origin differs from the landmark's");
  }
  if (point_views.size() != points.size()) {
    throw Error(what + ": " + std::to_string(point_views.size()) + " point views for " +
                std::to_string(points.size()) + " points");
  }
  const std::uint32_t all = (std::uint32_t{1} << view_origins.size()) - 1;
  for (const std::uint32_t mask : point_views) {
    if (mask == 0 || (mask & ~all) != 0) {
      throw Error(what + ": a point's views name no view or a view the landmark does not have");
    }
  }
}

Eigen::Vector3d default_up(const Eigen::Isometry3d& T_cloud_sensor, bool base_frame) {
  if (base_frame) return Eigen::Vector3d::UnitZ();
  return (T_cloud_sensor.linear() * -Eigen::Vector3d::UnitY()).normalized();
}

void estimate_landmark_normals(Landmark& landmark) {
  PointCloud& points = landmark.points;
  points.T_cloud_sensor.translation() = landmark.sensor_origin;
  // k = 10 at the 5 mm leaf: a 1.5 cm neighbourhood, enough to average out depth noise while
  // keeping the carton's edges sharp.
  points.normals = estimate_normals(points, KdTree(points), NormalSettings{10});
  if (!landmark.multi_view()) return;
  // A point the first view never saw faces the first view that did: a normal turned towards a
  // sensor that saw the point from its other side would hide it from every search.
  for (std::size_t i = 0; i < points.size(); ++i) {
    Eigen::Vector3f& n = points.normals[i];
    const std::uint32_t mask = landmark.point_views[i];
    if (!n.allFinite() || (mask & 1u) != 0) continue;
    const auto first = static_cast<std::size_t>(__builtin_ctz(mask));
    const Eigen::Vector3f to_sensor = landmark.view_origins[first].cast<float>() - points.points[i];
    if (n.dot(to_sensor) < 0.0f) n = -n;
  }
}

void prepare_landmark(Landmark& landmark, const std::vector<Eigen::Vector3f>* scene_points) {
  if (landmark.multi_view()) {
    // Without the views' frames (importing), each view's rays reach the points it measured.
    std::vector<std::vector<Eigen::Vector3f>> seen(landmark.view_origins.size());
    for (std::size_t i = 0; i < landmark.points.size(); ++i) {
      for (std::size_t v = 0; v < seen.size(); ++v) {
        if ((landmark.point_views[i] >> v) & 1u) seen[v].push_back(landmark.points.points[i]);
      }
    }
    std::vector<RayBundle> views;
    for (std::size_t v = 0; v < seen.size(); ++v) {
      views.push_back({&seen[v], landmark.view_origins[v]});
    }
    prepare_landmark_views(landmark, views);
    return;
  }
  prepare_landmark_views(landmark, {RayBundle{scene_points ? scene_points : &landmark.points.points,
                                              landmark.sensor_origin}});
}

void prepare_landmark_views(Landmark& landmark, const std::vector<RayBundle>& views) {
  estimate_landmark_normals(landmark);
  const PointCloud& points = landmark.points;
  const CaptureSettings& s = landmark.settings;
  landmark.distance = DistanceField(points.points, {s.leaf_size, s.distance_band});
  landmark.empty_space = EmptySpaceGrid::observe_views(
      views, landmark.box, landmark.distance, {s.leaf_size, s.empty_space_margin, s.leaf_size});
}

}  // namespace lmk
