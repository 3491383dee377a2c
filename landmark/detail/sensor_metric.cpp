#include "landmark/detail/sensor_metric.h"

#include <algorithm>
#include <cmath>

#include "landmark/detail/grid_metrics.h"
#include "landmark/landmark.h"
#include "landmark/scene_index.h"

namespace lmk {

namespace {

constexpr double kCap = 3.0;        // sigma: beyond, a residual says only "not here"
constexpr double kSupport = 2.0;    // sigma: a point this close to the scene surface is supported
constexpr double kOccluding = 3.0;  // sigma: a depth gap beyond noise, in front or behind
constexpr double kNoiseBand = 2.0;  // sigma: scene voxels this close to the landmark are its noise
constexpr double kMinVisibleShare = 0.2;
// A surface turned more than 80 degrees from its line of sight returns nothing to the sensor.
constexpr float kTurnedAway = 0.1736f;

}  // namespace

ErrorTerms sensor_metric(const SceneView& scene, const LandmarkView& landmark,
                         const Eigen::Isometry3d& T_scene_capture) {
  ErrorTerms terms;
  const SceneIndex& index = scene.index;
  const DepthNoise noise = index.settings().depth_noise();
  const std::optional<RangeImage>& image = index.range_image();
  const Eigen::Isometry3f T = T_scene_capture.cast<float>();
  const Eigen::Vector3f sensor = index.T_scene_sensor().translation().cast<float>();
  const Eigen::Vector3f capture_sensor = landmark.landmark.sensor_origin.cast<float>();
  const DistanceField::Sampler scene_field(index.field());
  const PointCloud& points = landmark.points;

  std::size_t supported = 0;
  for (std::size_t j = 0; j < points.size(); ++j) {
    const Eigen::Vector3f q = T * points.points[j];
    if (points.has_normals()) {
      const Eigen::Vector3f n = T.linear() * points.normals[j];
      if (n.allFinite() && n.dot((sensor - q).normalized()) < kTurnedAway) {
        ++terms.unseen_points;
        continue;
      }
    }
    const double capture_depth = (points.points[j] - capture_sensor).norm();
    double cost = 0.0;
    if (image) {
      const RangeImage::Look look = image->look(q);
      const double sigma = noise.residual_sigma(capture_depth, look.depth);
      if (!look.in_view || std::isnan(look.measured) ||
          look.measured - look.depth < -kOccluding * sigma) {
        ++terms.unseen_points;  // outside the view, no return, or behind a nearer surface
        continue;
      }
      const double gap = look.measured - look.depth;
      if (gap > kOccluding * sigma) {
        ++terms.seen_through_points;
        cost = kCap;
      } else {
        const double d = std::min<double>(landmark_point_distance(index, scene_field, T, points, j),
                                          std::abs(gap));
        cost = std::min(d / sigma, kCap);
      }
    } else {
      const double sigma = noise.residual_sigma(capture_depth, (q - sensor).norm());
      cost = std::min(landmark_point_distance(index, scene_field, T, points, j) / sigma, kCap);
    }
    terms.landmark_to_scene_sum += cost;
    ++terms.landmark_to_scene_count;
    if (cost < kSupport) ++supported;
  }
  const double expected = std::max(static_cast<double>(terms.landmark_to_scene_count),
                                   kMinVisibleShare * static_cast<double>(points.size()));
  terms.coverage = expected > 0.0 ? static_cast<double>(supported) / expected : 0.0;

  // Empty space, as the visibility metric tests it, with the landmark surface's noise band left
  // out: a scene point within noise of the surface is that surface measured again.
  const EmptySpaceGrid::Sampler empty(landmark.landmark.empty_space);
  const DistanceField::Sampler landmark_field(landmark.landmark.distance);
  const Eigen::Isometry3f T_capture_scene = T.inverse();
  terms.empty_space_probes = landmark.landmark.empty_space.size();
  double violation_distance = 0.0;
  for (const Eigen::Vector3f& occupied :
       index.occupancy().occupied_in(landmark.box.transformed(T_scene_capture))) {
    const Eigen::Vector3f e = T_capture_scene * occupied;
    if (!empty.is_empty(e)) continue;
    const double sigma =
        noise.residual_sigma((e - capture_sensor).norm(),
                             image ? image->depth_of(occupied) : (occupied - sensor).norm());
    const double d = landmark_field.distance(e);
    if (d < kNoiseBand * sigma) continue;
    ++terms.empty_space_violations;
    violation_distance += d;
    terms.scene_to_landmark_sum += std::min(d / sigma, kCap);
    ++terms.scene_to_landmark_count;
  }
  if (terms.empty_space_violations > 0) {
    terms.empty_space_violation_mean =
        violation_distance / static_cast<double>(terms.empty_space_violations);
  }
  terms.finish();
  return terms;
}

}  // namespace lmk
