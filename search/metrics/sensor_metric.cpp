// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/metrics/sensor_metric.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lmk/landmark/landmark.h"
#include "lmk/search/metrics/grid_metrics.h"
#include "lmk/search/scene_index.h"

namespace lmk {

namespace {

constexpr double kCap = 3.0;        // sigma: beyond, a residual says only "not here"
constexpr double kSupport = 2.0;    // sigma: a point this close to the scene surface is supported
constexpr double kOccluding = 3.0;  // sigma: a depth gap beyond noise, in front or behind
constexpr double kNoiseBand = 2.0;  // sigma: scene voxels this close to the landmark are its noise
constexpr double kMinVisibleShare = 0.2;
constexpr double kAtSurface = 1.0;  // sigma
// A landmark with free space must show at least this share of it to the scene's sensor beyond the
// noise: a pose whose free space cannot be seen (too far for its margins, or buried in a surface
// that hides it) has no evidence for it beyond a fit that the noise makes easy.
constexpr double kMinEmptyObserved = 0.02;

// What the scene's sensor saw of one observed-empty voxel of the landmark (its centre `c` and its
// distance from the landmark's surface), placed by the pose T: a surface measured at its depth
// occupies it; one clearly behind confirms it empty; one clearly in front hides it and, as outside
// the view or without a return, leaves it unknown. A voxel nearer the landmark's surface than that
// same margin of noise is not tested: the landmark's own surface, measured behind it, could not
// confirm it.
enum class EmptyVoxel { untested, seen_empty, occupied, unknown };

EmptyVoxel look_at_empty_voxel(const RangeImage& image, const DepthNoise& noise,
                               const Eigen::Vector3f& capture_sensor, const Eigen::Vector3f& c,
                               float distance, const Eigen::Isometry3f& T) {
  const RangeImage::Look look = image.look(T * c);
  const double sigma = noise.residual_sigma((c - capture_sensor).norm(), std::abs(look.depth));
  if (distance < kOccluding * sigma) return EmptyVoxel::untested;
  if (!look.in_view || std::isnan(look.measured)) return EmptyVoxel::unknown;
  const double gap = look.measured - look.depth;
  if (gap > kOccluding * sigma) return EmptyVoxel::seen_empty;
  // Further in front than a sigma, the voxel is hidden: the surface may be a side of the object
  // the capture never saw. Further behind, it may be the surface the voxel was seen empty in front
  // of at capture (a table under a bottle), which the landmark need not hold.
  return std::abs(gap) > kAtSurface * sigma ? EmptyVoxel::unknown : EmptyVoxel::occupied;
}

// Empty space seen from the scene's sensor (look_at_empty_voxel()): probes are the voxels observed
// either way, violations those occupied.
void projective_empty_space(const RangeImage& image, const DepthNoise& noise,
                            const Landmark& landmark, const std::vector<Eigen::Vector3f>& centres,
                            const std::vector<float>& distances, const Eigen::Isometry3f& T,
                            EmptySpaceTerms& terms) {
  const Eigen::Vector3f capture_sensor = landmark.sensor_origin.cast<float>();
  double violation_distance = 0.0;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const EmptyVoxel seen =
        look_at_empty_voxel(image, noise, capture_sensor, centres[i], distances[i], T);
    if (seen == EmptyVoxel::seen_empty) ++terms.probes;
    if (seen != EmptyVoxel::occupied) continue;
    ++terms.probes;
    ++terms.violations;
    violation_distance += distances[i];
  }
  if (terms.violations > 0) {
    terms.violation_mean = violation_distance / static_cast<double>(terms.violations);
  }
}

// Without a range image: the scene's occupied voxels in the box that fall in the landmark's
// observed-empty space, beyond the noise of its surface (probes: every empty voxel).
void occupied_empty_space(const SceneIndex& index, const DepthNoise& noise,
                          const LandmarkView& landmark, const Eigen::Isometry3d& T_scene_capture,
                          EmptySpaceTerms& terms) {
  const DistanceField::Sampler landmark_field(landmark.landmark.distance);
  const float band = static_cast<float>(landmark.landmark.distance.band());
  const Eigen::Vector3f capture_sensor = landmark.landmark.sensor_origin.cast<float>();
  const Eigen::Vector3f sensor = index.T_scene_sensor().translation().cast<float>();
  terms.probes = landmark.landmark.empty_space.size();
  double violation_distance = 0.0;
  for_each_occupied_empty_voxel(index, landmark, T_scene_capture,
                                [&](const Eigen::Vector3f& e, const Eigen::Vector3f& occupied) {
                                  const double sigma = noise.residual_sigma(
                                      (e - capture_sensor).norm(), (occupied - sensor).norm());
                                  const float d = landmark_field.distance(e);
                                  if (d < std::min<double>(kNoiseBand * sigma, 0.99 * band)) return;
                                  ++terms.violations;
                                  violation_distance += d;
                                });
  if (terms.violations > 0) {
    terms.violation_mean = violation_distance / static_cast<double>(terms.violations);
  }
}

}  // namespace

double SensorFit::mean_cost() const {
  const double total = static_cast<double>(visible + unseen);
  const double floor = kMinVisibleShare * total;
  const double shortfall = std::max(0.0, floor - static_cast<double>(visible));
  const double count = std::max(static_cast<double>(visible), floor);
  return count > 0.0 ? (cost_sum + kCap * shortfall) / count : kCap;
}

double SensorFit::coverage() const {
  const double expected = std::max(static_cast<double>(visible),
                                   kMinVisibleShare * static_cast<double>(visible + unseen));
  return expected > 0.0 ? static_cast<double>(supported) / expected : 0.0;
}

double empty_space_seen_empty(const SceneIndex& index, const Landmark& landmark,
                              const std::vector<float>& distances,
                              const Eigen::Isometry3d& T_scene_capture) {
  const std::vector<Eigen::Vector3f>& centres = landmark.empty_space.centres();
  if (!index.range_image() || centres.empty()) return std::numeric_limits<double>::quiet_NaN();
  const DepthNoise noise = index.settings().depth_noise();
  const Eigen::Vector3f capture_sensor = landmark.sensor_origin.cast<float>();
  const Eigen::Isometry3f T = T_scene_capture.cast<float>();
  std::size_t tested = 0, seen = 0;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const EmptyVoxel look = look_at_empty_voxel(*index.range_image(), noise, capture_sensor,
                                                centres[i], distances[i], T);
    if (look == EmptyVoxel::untested) continue;
    ++tested;
    if (look == EmptyVoxel::seen_empty) ++seen;
  }
  return tested > 0 ? static_cast<double>(seen) / static_cast<double>(tested)
                    : std::numeric_limits<double>::quiet_NaN();
}

double empty_space_penalty(const SceneIndex& index, const Landmark& landmark,
                           const std::vector<Eigen::Vector3f>& centres,
                           const std::vector<float>& distances,
                           const Eigen::Isometry3f& T_scene_capture) {
  if (!index.range_image() || centres.empty()) return 0.0;
  EmptySpaceTerms terms;
  projective_empty_space(*index.range_image(), index.settings().depth_noise(), landmark, centres,
                         distances, T_scene_capture, terms);
  const double observed = static_cast<double>(terms.probes) / static_cast<double>(centres.size());
  if (observed < kMinEmptyObserved) return kCap;
  return kCap * static_cast<double>(terms.violations) / static_cast<double>(terms.probes);
}

SensorFit sensor_fit(const SceneIndex& index, const PointCloud& points,
                     const Eigen::Vector3f& capture_sensor, const Eigen::Isometry3f& T) {
  SensorFit fit;
  const DepthNoise noise = index.settings().depth_noise();
  const RangeImage* image = index.range_image();
  const Eigen::Vector3f sensor = index.T_scene_sensor().translation().cast<float>();
  const DistanceField::Sampler scene_field(index.field());
  for (std::size_t j = 0; j < points.size(); ++j) {
    const Eigen::Vector3f q = T * points.points[j];
    if (turned_away(sensor, T, points, j)) {
      ++fit.unseen;
      continue;
    }
    const double capture_depth = (points.points[j] - capture_sensor).norm();
    double cost = 0.0;
    if (image) {
      const RangeImage::Look look = image->look(q);
      const double sigma = noise.residual_sigma(capture_depth, look.depth);
      if (!look.in_view || std::isnan(look.measured) ||
          look.measured - look.depth < -kOccluding * sigma) {
        ++fit.unseen;  // outside the view, no return, or behind a nearer surface
        continue;
      }
      const double gap = look.measured - look.depth;
      if (gap > kOccluding * sigma) {
        ++fit.seen_through;
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
    fit.cost_sum += cost;
    ++fit.visible;
    if (cost < kSupport) ++fit.supported;
  }
  return fit;
}

ErrorTerms sensor_metric(const SceneView& scene, const LandmarkView& landmark,
                         const Eigen::Isometry3d& T_scene_capture) {
  ErrorTerms terms;
  const SceneIndex& index = scene.index;
  const DepthNoise noise = index.settings().depth_noise();
  const RangeImage* image = index.range_image();
  const Eigen::Isometry3f T = T_scene_capture.cast<float>();
  const SensorFit fit =
      sensor_fit(index, landmark.points, landmark.landmark.sensor_origin.cast<float>(), T);
  // A pose that shows less than a fifth of the landmark pays the cap for each point short of it.
  const auto shortfall = static_cast<std::size_t>(std::ceil(
      std::max(0.0, kMinVisibleShare * static_cast<double>(landmark.points.size()) - fit.visible)));
  terms.landmark_to_scene_sum = fit.cost_sum + kCap * static_cast<double>(shortfall);
  terms.landmark_to_scene_count = fit.visible + shortfall;
  terms.support = SupportTerms{fit.coverage(), fit.unseen, fit.seen_through};
  EmptySpaceTerms& empty = terms.empty_space.emplace();

  if (image) {
    const std::vector<float> computed =
        landmark.empty_distances == nullptr
            ? empty_space_distances(landmark.landmark, landmark.tree)
            : std::vector<float>();
    projective_empty_space(
        *image, noise, landmark.landmark, landmark.landmark.empty_space.centres(),
        landmark.empty_distances ? *landmark.empty_distances : computed, T, empty);
  } else {
    occupied_empty_space(index, noise, landmark, T_scene_capture, empty);
  }
  const std::size_t empty_voxels = landmark.landmark.empty_space.size();
  if (image && empty_voxels > 0) {
    empty.observed = static_cast<double>(empty.probes) / static_cast<double>(empty_voxels);
    if (empty.observed < kMinEmptyObserved) {
      // Every point at the cap: the error says "no evidence", the terms say why.
      terms.landmark_to_scene_sum = kCap * static_cast<double>(terms.landmark_to_scene_count);
    }
  }
  terms.finish();
  return terms;
}

}  // namespace lmk
