// SPDX-License-Identifier: BSD-3-Clause
// Capture: a landmark cut out of one view of a scene with a box, or fused from several views of it
// (capture_views.h).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "lmk/geometry/error.h"
#include "lmk/geometry/filters.h"
#include "lmk/geometry/frame_preparation.h"
#include "lmk/geometry/kdtree.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/principal_axes.h"
#include "lmk/geometry/projector_shadow.h"
#include "lmk/geometry/voxel_grid.h"
#include "lmk/landmark/capture_views.h"
#include "lmk/landmark/landmark.h"

namespace lmk {
namespace {

std::string format_size(const Eigen::Vector3d& size) {
  std::ostringstream s;
  s << size.x() << " x " << size.y() << " x " << size.z() << " m";
  return s.str();
}

// One view's frame prepared as a search prepares its scene (SceneIndex), so that both sides are
// alike, and moved into the capture frame; with the ends of the rays that observed free space: to
// every point of the frame (non-finite ones are skipped) and through the projector's shadow.
struct PreparedView {
  PointCloud frame;
  std::vector<Eigen::Vector3f> ray_ends;
};

PreparedView prepare_view(const CaptureView& view, const CaptureSettings& settings) {
  const PointCloud& cloud = *view.cloud;
  std::optional<PointCloud> prepared =
      prepared_frame(cloud, settings.veil_angle, settings.depth_smoothing, DepthNoise());
  PreparedView out;
  out.frame = prepared ? std::move(*prepared) : cloud;
  std::vector<Eigen::Vector3f> shadow =
      projector_shadow_ray_ends(cloud, {settings.projector_baseline});
  // The first view usually is the capture frame: left untouched, its points stay bit for bit.
  if (!view.T_capture_cloud.matrix().isIdentity(0.0)) {
    out.frame = out.frame.transformed(view.T_capture_cloud);
    const Eigen::Isometry3f T = view.T_capture_cloud.cast<float>();
    for (Eigen::Vector3f& p : shadow) p = T * p;
  }
  out.ray_ends = out.frame.points;
  out.ray_ends.insert(out.ray_ends.end(), shadow.begin(), shadow.end());
  return out;
}

[[noreturn]] void throw_empty_box(const std::string& what, const Box& box) {
  const Eigen::Vector3d c = box.center();
  std::ostringstream s;
  s << what << ": no scene point inside the box centred at (" << c.x() << ", " << c.y() << ", "
    << c.z() << ") of " << format_size(box.size) << "; is it in the scene's frame?";
  throw Error(s.str());
}

// The views' points inside the box fused into one surface. The first view's points are the
// one-view landmark's, in its order. Each further view, downsampled alike, adds only the points
// farther than `merge` from every point so far: the surfaces no earlier view measured (a side
// turned away from them, a part beyond their image's edge). Its other points mark the nearest point
// so far as measured by it too. Merging voxel by voxel instead left two noisy samplings of one
// surface as a slab two or three voxels thick (a Kinect's noise at 2 m is about 7 mm), whose back
// layer a search then saw as hidden behind the front.
// Colour is kept when every view has it: a surface that only an uncoloured view measured would
// have none to compare.
void fuse_views(const std::vector<PointCloud>& insides, const std::vector<double>& merge,
                double leaf, Landmark& landmark) {
  landmark.points = voxel_downsample(insides.front(), leaf);
  landmark.point_views.assign(landmark.points.size(), 1u);
  const bool coloured = std::all_of(insides.begin(), insides.end(),
                                    [](const PointCloud& view) { return view.has_colors(); });
  if (!coloured) landmark.points.colors.clear();
  for (std::size_t v = 1; v < insides.size(); ++v) {
    const PointCloud view = voxel_downsample(insides[v], leaf);
    const KdTree so_far(landmark.points);
    const auto bit = std::uint32_t{1} << v;
    const auto reach = static_cast<float>(merge[v] * merge[v]);
    Indices added;
    for (std::size_t i = 0; i < view.size(); ++i) {
      const std::vector<Neighbor> nearest = so_far.knn(view.points[i], 1);
      if (!nearest.empty() && nearest.front().squared_distance <= reach) {
        landmark.point_views[nearest.front().index] |= bit;
      } else {
        added.push_back(static_cast<Index>(i));
      }
    }
    for (Index i : added) {
      landmark.points.points.push_back(view.points[i]);
      if (coloured) landmark.points.colors.push_back(view.colors[i]);
    }
    landmark.point_views.resize(landmark.points.size(), bit);
  }
  landmark.points.set_unorganized();
}

}  // namespace

void check_capture_settings(const CaptureSettings& s, const std::string& what) {
  validate_settings(s, what + ": ");
  if (!(s.distance_band >= s.leaf_size)) {
    throw Error(what + ": distance_band (--distance-band): " + std::to_string(s.distance_band) +
                " must be at least the leaf size (" + std::to_string(s.leaf_size) + ")");
  }
  if (!(s.distance_band <= kMaxDistanceBandLeaves * s.leaf_size)) {
    throw Error(what + ": distance_band (--distance-band): " + std::to_string(s.distance_band) +
                " must be at most " + std::to_string(static_cast<int>(kMaxDistanceBandLeaves)) +
                " leaves (" + std::to_string(kMaxDistanceBandLeaves * s.leaf_size) + " m)");
  }
}

void prepare_capture_as_search(const SceneSettings& scene, CaptureSettings& capture) {
  capture.up = scene.up;
  capture.base_frame = scene.base_frame;
  capture.veil_angle = scene.veil_angle;
  capture.depth_smoothing = scene.depth_smoothing;
}

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

Landmark capture(const PointCloud& scene, const Box& box, const std::string& name,
                 const CaptureSettings& settings) {
  return capture_views({CaptureView{&scene, Eigen::Isometry3d::Identity()}}, box, name, settings);
}

Landmark capture_views(const std::vector<CaptureView>& views, const Box& box,
                       const std::string& name, const CaptureSettings& settings) {
  const std::string what = "capture '" + name + "'";
  if (name.empty()) throw Error("capture: the landmark needs a name");
  check_capture_settings(settings, what);
  check_capture_box(box, settings, what);
  if (views.empty() || views.size() > kMaxLandmarkViews) {
    throw Error(what + ": a landmark takes 1 to " + std::to_string(kMaxLandmarkViews) +
                " views, not " + std::to_string(views.size()));
  }
  for (std::size_t v = 0; v < views.size(); ++v) {
    if (views[v].cloud == nullptr || !is_valid_pose(views[v].T_capture_cloud)) {
      throw Error(what + ": view " + std::to_string(v + 1) +
                  " needs a cloud and a finite pose with a proper rotation");
    }
  }
  std::vector<PreparedView> prepared;
  std::vector<PointCloud> insides;
  for (std::size_t v = 0; v < views.size(); ++v) {
    prepared.push_back(prepare_view(views[v], settings));
    insides.push_back(crop(prepared.back().frame, box));
    if (insides.back().empty()) {
      if (views.size() == 1) throw_empty_box(what, box);
      throw Error(what + ": view " + std::to_string(v + 1) +
                  " has no point inside the box; is its pose right, and does it see the landmark?");
    }
  }
  Landmark landmark;
  landmark.name = name;
  const PointCloud& first = prepared.front().frame;
  if (views.size() == 1) {
    landmark.points = voxel_downsample(insides.front(), settings.leaf_size);
  } else {
    // Two points of one surface seen from two views lie within the noise of either: three sigma
    // of the farther view's depth at the box, and at least two leaves.
    std::vector<double> merge;
    for (const PreparedView& view : prepared) {
      const double range = (box.center() - view.frame.sensor_origin()).norm();
      merge.push_back(
          std::max(2.0 * settings.leaf_size, 3.0 * DepthNoise().measurement_sigma(range)));
    }
    fuse_views(insides, merge, settings.leaf_size, landmark);
    for (const PreparedView& view : prepared) {
      landmark.view_origins.push_back(view.frame.sensor_origin());
    }
  }
  if (landmark.points.size() < settings.min_points) {
    throw Error(what + ": only " + std::to_string(landmark.points.size()) +
                " points in the box after downsampling, fewer than the minimum of " +
                std::to_string(settings.min_points) + "; draw a larger box or lower min_points");
  }
  if (const auto why =
          degenerate_shape(landmark.points, settings.leaf_size, what, settings.allow_flat)) {
    throw Error(*why);
  }
  landmark.points.T_cloud_sensor = first.T_cloud_sensor;
  landmark.box = box;
  landmark.sensor_origin = first.sensor_origin();
  landmark.settings = settings;
  landmark.up = settings.up ? settings.up->normalized()
                            : default_up(first.T_cloud_sensor, settings.base_frame);
  std::vector<RayBundle> rays;
  for (const PreparedView& view : prepared) {
    rays.push_back({&view.ray_ends, view.frame.sensor_origin()});
  }
  prepare_landmark_views(landmark, rays);
  return landmark;
}

namespace {

// At least this share of a landmark's points within two leaves of one plane (or one line) makes
// its shape flat (or straight).
constexpr double kDegenerateFraction = 0.95;

// The shares of `points` near their best plane and near their best line, with that plane's normal.
struct ShapeShares {
  Eigen::Vector3d normal;
  double near_plane = 0.0, near_line = 0.0;
  double tolerance = 0.0;  ///< the distance counted as near, m
};

ShapeShares shape_shares(const PointCloud& points, double leaf_size) {
  const PrincipalAxes pca =
      principal_axes(points.size(), [&](std::size_t i) { return points.points[i]; });
  const Eigen::Vector3d mean = pca.mean, axis = pca.axes.col(2);
  ShapeShares s;
  s.normal = pca.axes.col(0);
  s.tolerance = 2.0 * leaf_size;
  std::size_t near_plane = 0, near_line = 0;
  for (const auto& p : points.points) {
    const Eigen::Vector3d d = p.cast<double>() - mean;
    if (std::abs(d.dot(s.normal)) <= s.tolerance) ++near_plane;
    if ((d - d.dot(axis) * axis).norm() <= s.tolerance) ++near_line;
  }
  const double n = static_cast<double>(points.size());
  s.near_plane = static_cast<double>(near_plane) / n;
  s.near_line = static_cast<double>(near_line) / n;
  return s;
}

}  // namespace

std::optional<Eigen::Vector3d> flat_normal(const PointCloud& points, double leaf_size) {
  if (points.size() < 3) return std::nullopt;
  const ShapeShares s = shape_shares(points, leaf_size);
  if (s.near_plane < kDegenerateFraction || s.near_line >= kDegenerateFraction) return std::nullopt;
  return s.normal;
}

std::optional<std::string> degenerate_shape(const PointCloud& points, double leaf_size,
                                            const std::string& what, bool allow_flat) {
  if (points.size() < 3) return what + ": fewer than three points cannot fix a pose";
  const ShapeShares s = shape_shares(points, leaf_size);
  const auto percent = [](double share) { return std::to_string(std::lround(100.0 * share)); };
  const std::string within = " within " + std::to_string(std::lround(1000.0 * s.tolerance)) + " mm";
  if (s.near_line >= kDegenerateFraction) {
    return what + ": the shape is a thin straight piece (" + percent(s.near_line) +
           "% of the points" + within +
           " of one line), which leaves its turn about that line undetermined; draw the "
           "box around something with a corner or some width";
  }
  if (s.near_plane >= kDegenerateFraction && !allow_flat) {
    return what + ": the shape is flat (" + percent(s.near_plane) + "% of the points" + within +
           " of one plane), so it would match anywhere on any plane; draw the box to include an "
           "edge, a corner or some relief, or capture it as a flat patch (--allow-flat)";
  }
  return std::nullopt;
}

}  // namespace lmk
