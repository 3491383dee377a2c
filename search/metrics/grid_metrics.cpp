// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/metrics/grid_metrics.h"

#include <algorithm>
#include <cmath>

#include "lmk/landmark/landmark.h"
#include "lmk/search/scene_index.h"

namespace lmk {

float scene_surface_distance(const SceneIndex& scene, const DistanceField::Sampler& field,
                             const Eigen::Vector3f& q, const Eigen::Vector3f* normal) {
  constexpr float kBackFacing = -0.5f;  // cos(120 degrees)
  const float band = static_cast<float>(scene.field().band());
  const int index = field.closest(q);
  if (index < 0) return band;
  const Eigen::Vector3f delta = q - scene.coarse().points[static_cast<std::size_t>(index)];
  const Eigen::Vector3f& n = scene.coarse().normals[static_cast<std::size_t>(index)];
  if (!n.allFinite()) return std::min(band, delta.norm());
  if (normal != nullptr && normal->allFinite() && normal->dot(n) < kBackFacing) return band;
  const float along = n.dot(delta);
  const float lateral = std::sqrt(std::max(0.0f, delta.squaredNorm() - along * along));
  const float slack = static_cast<float>(0.5 * std::sqrt(3.0) * scene.settings().coarse_leaf);
  const float beside = std::max(0.0f, lateral - slack);
  return std::min(band, std::sqrt(along * along + beside * beside));
}

float landmark_point_distance(const SceneIndex& scene, const DistanceField::Sampler& field,
                              const Eigen::Isometry3f& T_scene_capture, const PointCloud& landmark,
                              std::size_t j) {
  const Eigen::Vector3f q = T_scene_capture * landmark.points[j];
  if (!landmark.has_normals()) return scene_surface_distance(scene, field, q);
  const Eigen::Vector3f normal = T_scene_capture.linear() * landmark.normals[j];
  return scene_surface_distance(scene, field, q, &normal);
}

ErrorTerms vdb_metric(const SceneView& scene, const LandmarkView& landmark,
                      const Eigen::Isometry3d& T_scene_capture) {
  ErrorTerms terms;
  const Indices in_box = scene_points_in_box(scene, landmark.box.transformed(T_scene_capture));
  terms.scene_points_in_box = in_box.size();
  const DistanceField::Sampler landmark_field(landmark.landmark.distance);
  std::vector<char> visited(landmark.points.size(), 0);
  const Eigen::Isometry3f T_capture_scene = T_scene_capture.inverse().cast<float>();
  for (Index i : in_box) {
    const Eigen::Vector3f p = T_capture_scene * scene.points().points[i];
    terms.scene_to_landmark_sum += landmark_field.distance(p);
    ++terms.scene_to_landmark_count;
    const int closest = landmark_field.closest(p);
    if (closest >= 0) visited[static_cast<std::size_t>(closest)] = 1;
  }
  const DistanceField::Sampler scene_field(scene.index.field());
  const Eigen::Isometry3f T = T_scene_capture.cast<float>();
  for (std::size_t j = 0; j < landmark.points.size(); ++j) {
    if (visited[j]) continue;
    terms.landmark_to_scene_sum +=
        scene_surface_distance(scene.index, scene_field, T * landmark.points.points[j]);
    ++terms.landmark_to_scene_count;
  }
  terms.finish();
  return terms;
}

Box occluder_free_zone(const Box& box) {
  return Box(box.pose, box.size + Eigen::Vector3d::Constant(2.0 * kOccluderClearance));
}

bool hidden_behind(const SceneIndex& scene, const Eigen::Vector3f& q, const Box& free_zone) {
  const RangeImage* image = scene.range_image();
  if (!image) return false;
  const RangeImage::Look look = image->look(q);
  if (!look.in_view || std::isnan(look.measured)) return false;
  const double margin = std::max(3.0 * scene.settings().depth_noise().measurement_sigma(look.depth),
                                 2.0 * scene.settings().leaf_size);
  if (!(look.measured < look.depth - margin)) return false;
  // The surface measured along the point's ray (depths along the optical axis scale with the
  // distance along the ray).
  const Eigen::Vector3f sensor = scene.T_scene_sensor().translation().cast<float>();
  const Eigen::Vector3f seen =
      sensor + (q - sensor) * static_cast<float>(look.measured / look.depth);
  return !free_zone.contains(Eigen::Vector3d(seen.cast<double>()));
}

bool unseen_by_sensor(const SceneIndex& scene, const Eigen::Vector3f& q, UnseenPoints which) {
  if (which == UnseenPoints::counted || !scene.organised()) return false;
  const RangeImage* image = scene.range_image();
  if (!image) return false;  // no pinhole view from its recorded pose
  const RangeImage::Look look = image->look(q);
  return !look.in_view || (which == UnseenPoints::no_return && std::isnan(look.measured));
}

std::size_t shown_shortfall(std::size_t shown, std::size_t total) {
  const double floor = kMinShownShare * static_cast<double>(total);
  return static_cast<std::size_t>(std::ceil(std::max(0.0, floor - static_cast<double>(shown))));
}

std::vector<char> self_hidden(const PointCloud& points, const Eigen::Isometry3f& T_scene_capture,
                              const Eigen::Vector3f& sensor, const Eigen::Vector3f& centre,
                              double spacing) {
  const std::size_t n = points.size();
  std::vector<char> hidden(n, 0);
  const Eigen::Vector3f axis = (centre - sensor).normalized();
  const float range = (centre - sensor).norm();
  if (!(range > 0.0f) || n == 0) return hidden;
  // The image plane's axes, any two perpendicular to the ray to the centre.
  const Eigen::Vector3f e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
  const float cell = static_cast<float>(spacing) / range;  // in the plane at unit depth
  std::vector<float> depth(n);
  std::vector<std::pair<int, int>> pixel(n);
  int u_min = std::numeric_limits<int>::max(), v_min = u_min, u_max = -u_min, v_max = -u_min;
  for (std::size_t j = 0; j < n; ++j) {
    const Eigen::Vector3f d = T_scene_capture * points.points[j] - sensor;
    depth[j] = d.dot(axis);
    if (!(depth[j] > 0.0f)) continue;
    pixel[j] = {static_cast<int>(std::floor(d.dot(e1) / depth[j] / cell)),
                static_cast<int>(std::floor(d.dot(e2) / depth[j] / cell))};
    u_min = std::min(u_min, pixel[j].first), u_max = std::max(u_max, pixel[j].first);
    v_min = std::min(v_min, pixel[j].second), v_max = std::max(v_max, pixel[j].second);
  }
  if (u_min > u_max) return hidden;
  const int width = u_max - u_min + 3, height = v_max - v_min + 3;  // a cell of border each side
  std::vector<float> nearest(static_cast<std::size_t>(width) * static_cast<std::size_t>(height),
                             std::numeric_limits<float>::infinity());
  const auto at = [&](int u, int v) -> float& {
    return nearest[static_cast<std::size_t>(v - v_min + 1) * static_cast<std::size_t>(width) +
                   static_cast<std::size_t>(u - u_min + 1)];
  };
  for (std::size_t j = 0; j < n; ++j) {
    if (depth[j] > 0.0f)
      at(pixel[j].first, pixel[j].second) = std::min(at(pixel[j].first, pixel[j].second), depth[j]);
  }
  for (std::size_t j = 0; j < n; ++j) {
    if (!(depth[j] > 0.0f)) continue;
    float front = std::numeric_limits<float>::infinity();
    for (int du = -1; du <= 1; ++du)
      for (int dv = -1; dv <= 1; ++dv)
        front = std::min(front, at(pixel[j].first + du, pixel[j].second + dv));
    // A surface seen obliquely recedes across the window by itself: its own slope (tan of the
    // angle between its normal and the ray) over the two cells and a half between a point and the
    // farthest one of its window is not an occluder's gap.
    float slope = 0.0f;
    if (points.has_normals() && points.normals[j].allFinite()) {
      const Eigen::Vector3f ray = (T_scene_capture * points.points[j] - sensor).normalized();
      const float c = std::max(std::abs((T_scene_capture.linear() * points.normals[j]).dot(ray)),
                               kTurnedAwayCos);
      slope = std::sqrt(1.0f - c * c) / c;
    }
    hidden[j] = depth[j] > front + static_cast<float>(spacing) * (1.0f + 2.5f * slope);
  }
  return hidden;
}

std::vector<char> facing_sensor(const PointCloud& points, const Eigen::Isometry3f& T_scene_capture,
                                const Eigen::Vector3f& sensor, const Eigen::Vector3f& centre,
                                double spacing) {
  std::vector<char> facing = self_hidden(points, T_scene_capture, sensor, centre, spacing);
  for (std::size_t j = 0; j < points.size(); ++j) {
    facing[j] = !facing[j] && !turned_away(sensor, T_scene_capture, points, j);
  }
  return facing;
}

UnseenPoints unseen_points_of(const SceneIndex& scene, const Landmark& landmark) {
  const UnseenPoints set = scene.settings().unseen_points;
  return landmark.multi_view() && set == UnseenPoints::counted ? UnseenPoints::outside_image : set;
}

bool turned_away(const Eigen::Vector3f& sensor, const Eigen::Isometry3f& T_scene_capture,
                 const PointCloud& points, std::size_t j) {
  if (!points.has_normals()) return false;
  const Eigen::Vector3f n = T_scene_capture.linear() * points.normals[j];
  const Eigen::Vector3f q = T_scene_capture * points.points[j];
  return n.allFinite() && n.dot((sensor - q).normalized()) < kTurnedAwayCos;
}

double mean_surface_distance(const SceneIndex& scene, const PointCloud& points,
                             const Eigen::Isometry3f& T_scene_capture, const Box* capture_box,
                             const SeveralViews* views) {
  const bool facing_only = views != nullptr;
  const DistanceField::Sampler field(scene.field());
  const bool projective = capture_box != nullptr;
  const Box free_zone =
      projective ? occluder_free_zone(capture_box->transformed(T_scene_capture.cast<double>()))
                 : Box();
  const Eigen::Vector3f sensor = scene.T_scene_sensor().translation().cast<float>();
  const std::vector<char> shows =
      facing_only
          ? facing_sensor(points, T_scene_capture, sensor,
                          (T_scene_capture.cast<double>() * views->box_centre).cast<float>(),
                          views->spacing)
          : std::vector<char>();
  double sum = 0.0;
  std::size_t shown = 0, facing = 0;
  for (std::size_t j = 0; j < points.size(); ++j) {
    if (facing_only && (!shows[j] || unseen_by_sensor(scene, T_scene_capture * points.points[j],
                                                      UnseenPoints::outside_image))) {
      continue;
    }
    ++facing;
    if (projective && hidden_behind(scene, T_scene_capture * points.points[j], free_zone)) {
      continue;
    }
    sum += landmark_point_distance(scene, field, T_scene_capture, points, j);
    ++shown;
  }
  const std::size_t shortfall = shown_shortfall(shown, facing);
  const std::size_t count = shown + shortfall;
  return count == 0 ? scene.field().band()
                    : (sum + scene.field().band() * static_cast<double>(shortfall)) /
                          static_cast<double>(count);
}

double expected_match_error(const SceneSettings& settings, double range) {
  // Shares of the coarse leaf and of one depth measurement's sigma, fitted to the viewpoints
  // preset's true matches (the figures are in grid_metrics.h).
  constexpr double kResolutionShare = 0.28;
  constexpr double kNoiseShare = 0.4;
  return std::hypot(kResolutionShare * settings.coarse_leaf,
                    kNoiseShare * settings.depth_noise().measurement_sigma(range));
}

double match_error_scale(const SceneSettings& settings, double range) {
  if (!settings.threshold_range || !(range > *settings.threshold_range)) return 1.0;
  return expected_match_error(settings, *settings.threshold_range) /
         expected_match_error(settings, range);
}

namespace {

// The visibility metric's terms, with or without hiding the points behind nearer surfaces.
ErrorTerms visibility_terms(const SceneView& scene, const LandmarkView& landmark,
                            const Eigen::Isometry3d& T_scene_capture, bool projective) {
  ErrorTerms terms;
  SupportTerms& seen = terms.support.emplace();
  EmptySpaceTerms& empty = terms.empty_space.emplace();
  const Eigen::Isometry3f T = T_scene_capture.cast<float>();
  const DistanceField::Sampler scene_field(scene.index.field());
  const Box free_zone =
      projective ? occluder_free_zone(landmark.box.transformed(T_scene_capture)) : Box();
  // Support: a scene surface within two paper leaves (1 cm) of the landmark point.
  const float support = static_cast<float>(2.0 * scene.index.settings().leaf_size);
  std::size_t supported = 0, facing = 0;
  // A landmark of several views shows a sensor only its side turned towards it, and only the part
  // inside its image: other views saw beyond the image's edge of any one.
  const bool facing_only = landmark.landmark.multi_view();
  const UnseenPoints unseen = unseen_points_of(scene.index, landmark.landmark);
  const Eigen::Vector3f sensor = scene.index.T_scene_sensor().translation().cast<float>();
  const std::vector<char> shows =
      facing_only ? facing_sensor(landmark.points, T, sensor,
                                  (T_scene_capture * landmark.box.center()).cast<float>(),
                                  2.0 * landmark.landmark.settings.leaf_size)
                  : std::vector<char>();
  for (std::size_t j = 0; j < landmark.points.size(); ++j) {
    if (facing_only && !shows[j]) {
      ++seen.unseen_points;
      continue;
    }
    ++facing;
    const Eigen::Vector3f q = T * landmark.points.points[j];
    if ((projective && hidden_behind(scene.index, q, free_zone)) ||
        unseen_by_sensor(scene.index, q, unseen)) {
      ++seen.unseen_points;
      continue;
    }
    const float d = landmark_point_distance(scene.index, scene_field, T, landmark.points, j);
    terms.landmark_to_scene_sum += d;
    ++terms.landmark_to_scene_count;
    if (d < support) ++supported;
  }
  // Points short of the share a pose must show cost the band each (none for the visibility
  // metric, which shows every point).
  const std::size_t shortfall = shown_shortfall(terms.landmark_to_scene_count, facing);
  terms.landmark_to_scene_sum += scene.index.field().band() * static_cast<double>(shortfall);
  terms.landmark_to_scene_count += shortfall;
  seen.coverage =
      terms.landmark_to_scene_count == 0
          ? 0.0
          : static_cast<double>(supported) / static_cast<double>(terms.landmark_to_scene_count);

  // Empty space, from the scene's side: its occupied voxels that land in the landmark's
  // observed-empty voxels.
  const DistanceField::Sampler landmark_field(landmark.landmark.distance);
  empty.probes = landmark.landmark.empty_space.size();
  for_each_occupied_empty_voxel(scene.index, landmark, T_scene_capture,
                                [&](const Eigen::Vector3f& e, const Eigen::Vector3f&) {
                                  ++empty.violations;
                                  terms.scene_to_landmark_sum += landmark_field.distance(e);
                                  ++terms.scene_to_landmark_count;
                                });
  if (empty.violations > 0) {
    empty.violation_mean = terms.scene_to_landmark_sum / static_cast<double>(empty.violations);
  }
  // Far from the sensor, the noise raises every term of a true match: judge the candidate as if
  // it stood at the range the threshold was set for.
  const double range =
      (T_scene_capture * landmark.box.center() - scene.index.T_scene_sensor().translation()).norm();
  terms.range_scale = match_error_scale(scene.index.settings(), range);
  terms.finish();
  return terms;
}

}  // namespace

ErrorTerms visibility_metric(const SceneView& scene, const LandmarkView& landmark,
                             const Eigen::Isometry3d& T_scene_capture) {
  return visibility_terms(scene, landmark, T_scene_capture, false);
}

ErrorTerms projective_metric(const SceneView& scene, const LandmarkView& landmark,
                             const Eigen::Isometry3d& T_scene_capture) {
  return visibility_terms(scene, landmark, T_scene_capture, true);
}

}  // namespace lmk
