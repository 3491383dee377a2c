// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/landmark.h"

#include <cmath>
#include <sstream>

#include "lmk/geometry/error.h"
#include "lmk/geometry/filters.h"
#include "lmk/geometry/frame_preparation.h"
#include "lmk/geometry/kdtree.h"
#include "lmk/geometry/normals.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/principal_axes.h"
#include "lmk/geometry/projector_shadow.h"
#include "lmk/geometry/voxel_grid.h"

namespace lmk {
namespace {

std::string format_size(const Eigen::Vector3d& size) {
  std::ostringstream s;
  s << size.x() << " x " << size.y() << " x " << size.z() << " m";
  return s.str();
}

void check_settings(const CaptureSettings& s, const std::string& what) {
  if (!(s.leaf_size >= kMinLeafSize) || !std::isfinite(s.leaf_size)) {
    throw Error(what + ": leaf size must be finite and at least " +
                std::to_string(static_cast<int>(kMinLeafSize * 1000)) + " mm");
  }
  if (!(s.distance_band >= s.leaf_size) || !std::isfinite(s.distance_band)) {
    throw Error(what + ": the distance band must be finite and at least the leaf size");
  }
  if (!(s.empty_space_margin >= 0.0) || !std::isfinite(s.empty_space_margin)) {
    throw Error(what + ": the empty-space margin must be finite and non-negative");
  }
  if (!(s.veil_angle >= 0.0) || !(s.veil_angle < 1.5)) {
    throw Error(what + ": the veil angle must be in [0, 1.5) rad (0: keep veil points)");
  }
  if (s.depth_smoothing < 0 || s.depth_smoothing > kMaxDepthSmoothingRadius) {
    throw Error(what + ": the depth smoothing must be 0 to " +
                std::to_string(kMaxDepthSmoothingRadius) + " pixels (0: the raw depth)");
  }
  if (!(s.projector_baseline >= 0.0) || !std::isfinite(s.projector_baseline)) {
    throw Error(what + ": the projector baseline must be finite and non-negative (0: none)");
  }
  if (s.up && (!s.up->allFinite() || s.up->norm() < 1e-9)) {
    throw Error(what + ": the up axis must be a finite non-zero vector");
  }
  if (!(s.max_box_side > 0.0) || !std::isfinite(s.max_box_side)) {
    throw Error(what + ": maximum box side must be positive and finite");
  }
}

}  // namespace

void check_capture_box(const Box& box, const CaptureSettings& s, const std::string& what) {
  if (!box.size.allFinite() || (box.size.array() <= 0.0).any()) {
    throw Error(what + ": box sides must be positive and finite, got " + format_size(box.size));
  }
  if (!is_valid_pose(box.pose)) {
    throw Error(what + ": box pose must be finite with a proper rotation");
  }
  if ((box.size.array() > s.max_box_side).any()) {
    throw Error(what + ": box of " + format_size(box.size) + " has a side over the " +
                std::to_string(s.max_box_side) + " m limit (raise max_box_side if intended)");
  }
}

void Landmark::validate(const std::string& what) const {
  if (format_version != kLandmarkFormatVersion) {
    throw Error(what + ": landmark format version " + std::to_string(format_version) +
                " is not supported (this lmk reads version " +
                std::to_string(kLandmarkFormatVersion) + ")");
  }
  if (name.empty()) throw Error(what + ": landmark name is empty");
  check_settings(settings, what);
  check_capture_box(box, settings, what);
  if (!sensor_origin.allFinite()) throw Error(what + ": sensor origin is not finite");
  if (!up.allFinite() || std::abs(up.norm() - 1.0) > 1e-6) {
    throw Error(what + ": the up axis must be a finite unit vector");
  }
  if (points.empty()) throw Error(what + ": landmark has no points");
  if (points.count_finite() != points.size()) {
    throw Error(what + ": landmark points must all be finite");
  }
  points.validate(what);
}

Landmark capture(const PointCloud& scene, const Box& box, const std::string& name,
                 const CaptureSettings& settings) {
  const std::string what = "capture '" + name + "'";
  if (name.empty()) throw Error("capture: the landmark needs a name");
  check_settings(settings, what);
  check_capture_box(box, settings, what);
  // As a search prepares its scene (SceneIndex), so that both sides are alike.
  const std::optional<PointCloud> prepared =
      prepared_frame(scene, settings.veil_angle, settings.depth_smoothing, DepthNoise());
  const PointCloud& frame = prepared ? *prepared : scene;
  const PointCloud inside = crop(frame, box);
  if (inside.empty()) {
    const Eigen::Vector3d c = box.center();
    std::ostringstream s;
    s << what << ": no scene point inside the box centred at (" << c.x() << ", " << c.y() << ", "
      << c.z() << ") of " << format_size(box.size) << "; is it in the scene's frame?";
    throw Error(s.str());
  }
  Landmark landmark;
  landmark.name = name;
  landmark.points = voxel_downsample(inside, settings.leaf_size);
  if (landmark.points.size() < settings.min_points) {
    throw Error(what + ": only " + std::to_string(landmark.points.size()) +
                " points in the box after downsampling, fewer than the minimum of " +
                std::to_string(settings.min_points) + "; draw a larger box or lower min_points");
  }
  if (const auto why =
          degenerate_shape(landmark.points, settings.leaf_size, what, settings.allow_flat)) {
    throw Error(*why);
  }
  landmark.points.T_cloud_sensor = scene.T_cloud_sensor;
  landmark.box = box;
  landmark.sensor_origin = scene.sensor_origin();
  landmark.settings = settings;
  landmark.up = settings.up ? settings.up->normalized()
                            : default_up(scene.T_cloud_sensor, settings.base_frame);
  // Rays to every scene point (non-finite ones are skipped), and through the projector's shadow.
  std::vector<Eigen::Vector3f> rays = frame.points;
  const std::vector<Eigen::Vector3f> shadow =
      projector_shadow_ray_ends(scene, {settings.projector_baseline});
  rays.insert(rays.end(), shadow.begin(), shadow.end());
  prepare_landmark(landmark, &rays);
  return landmark;
}

std::optional<std::string> degenerate_shape(const PointCloud& points, double leaf_size,
                                            const std::string& what, bool allow_flat) {
  constexpr double kDegenerateFraction = 0.95;
  if (points.size() < 3) return what + ": fewer than three points cannot fix a pose";
  const PrincipalAxes pca =
      principal_axes(points.size(), [&](std::size_t i) { return points.points[i]; });
  const Eigen::Vector3d mean = pca.mean, normal = pca.axes.col(0), axis = pca.axes.col(2);
  const double tolerance = 2.0 * leaf_size;
  std::size_t near_plane = 0, near_line = 0;
  for (const auto& p : points.points) {
    const Eigen::Vector3d d = p.cast<double>() - mean;
    if (std::abs(d.dot(normal)) <= tolerance) ++near_plane;
    if ((d - d.dot(axis) * axis).norm() <= tolerance) ++near_line;
  }
  const auto share = [&](std::size_t n) {
    return static_cast<double>(n) / static_cast<double>(points.size());
  };
  const auto percent = [&](std::size_t n) { return std::to_string(std::lround(100.0 * share(n))); };
  const std::string within = " within " + std::to_string(std::lround(1000.0 * tolerance)) + " mm";
  if (share(near_line) >= kDegenerateFraction) {
    return what + ": the shape is a thin straight piece (" + percent(near_line) +
           "% of the points" + within +
           " of one line), which leaves its turn about that line undetermined; draw the "
           "box around something with a corner or some width";
  }
  if (share(near_plane) >= kDegenerateFraction && !allow_flat) {
    return what + ": the shape is flat (" + percent(near_plane) + "% of the points" + within +
           " of one plane), so it would match anywhere on any plane; draw the box to include an "
           "edge, a corner or some relief, or capture it as a flat patch (--allow-flat)";
  }
  return std::nullopt;
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
}

void prepare_landmark(Landmark& landmark, const std::vector<Eigen::Vector3f>* scene_points) {
  estimate_landmark_normals(landmark);
  const PointCloud& points = landmark.points;
  const CaptureSettings& s = landmark.settings;
  landmark.distance = DistanceField(points.points, {s.leaf_size, s.distance_band});
  landmark.empty_space = EmptySpaceGrid::observe(
      scene_points ? *scene_points : points.points, landmark.sensor_origin, landmark.box,
      landmark.distance, {s.leaf_size, s.empty_space_margin, s.leaf_size});
}

}  // namespace lmk
