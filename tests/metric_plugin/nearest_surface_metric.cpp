// SPDX-License-Identifier: BSD-3-Clause
// A metric plugin, as a researcher would write one (docs/developing.md, "Adding an error metric"):
// "nearest", the mean distance of the landmark's points to the nearest scene point, capped, with a
// coarse score of its own. Loaded through $LMK_METRIC_PLUGINS by lmk's own tools and Python, it
// shows that a metric needs nothing outside its file and its registration.

#include <algorithm>
#include <cmath>

#include "lmk/search/metrics/error_metrics.h"
#include "lmk/search/scene_index.h"

namespace {

// A point further than this from every scene point is simply unsupported.
constexpr double kCap = 0.02;

// The mean capped distance of `points` placed by T to the nearest point of `scene`.
double mean_nearest(const lmk::KdTree& scene, const std::vector<Eigen::Vector3f>& points,
                    const Eigen::Isometry3f& T, std::size_t* counted = nullptr) {
  double sum = 0.0;
  std::size_t n = 0;
  for (const Eigen::Vector3f& p : points) {
    const auto nearest = scene.nearest(T * p);
    if (!nearest) continue;
    sum += std::min<double>(std::sqrt(nearest->squared_distance), kCap);
    ++n;
  }
  if (counted) *counted = n;
  return n == 0 ? kCap : sum / static_cast<double>(n);
}

lmk::ErrorTerms nearest_surface(const lmk::SceneView& scene, const lmk::LandmarkView& landmark,
                                const Eigen::Isometry3d& T_scene_capture) {
  lmk::ErrorTerms terms;
  terms.landmark_to_scene_sum =
      mean_nearest(scene.tree(), landmark.points.points, T_scene_capture.cast<float>(),
                   &terms.landmark_to_scene_count) *
      static_cast<double>(terms.landmark_to_scene_count);
  terms.finish();
  return terms;
}

// The same measure over the few hundred points of the coarse model.
lmk::CoarseScore nearest_surface_coarse(const lmk::CoarseView& view) {
  const lmk::KdTree* scene = &view.index.fine_tree();
  const std::vector<Eigen::Vector3f>* points = &view.sparse_model.points;
  return [scene, points](const Eigen::Isometry3f& T) { return mean_nearest(*scene, *points, T); };
}

}  // namespace

extern "C" void lmk_register_error_metrics() {
  lmk::ErrorMetric m;
  m.name = "nearest";
  m.description = "test plugin: mean distance of the landmark's points to the nearest scene point";
  m.evaluate = nearest_surface;
  m.default_threshold = 0.004;
  m.coarse_score = nearest_surface_coarse;
  m.prune_ratio = 3.0;
  lmk::register_error_metric(std::move(m));
}
