// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/metrics/coarse_scores.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "lmk/search/fast/thinning.h"
#include "lmk/search/metrics/grid_metrics.h"
#include "lmk/search/metrics/sensor_metric.h"

namespace lmk::detail {

CoarseScoreFactory surface_distance_coarse_score(bool hide_occluded) {
  return [hide_occluded](const CoarseView& view) -> CoarseScore {
    // A landmark of several views: the thinned points lie further apart than the leaf, and hide
    // each other only across that spacing.
    const SeveralViews views{
        view.landmark.box.center(),
        2.0 * view.coarse_leaf *
            std::sqrt(std::max(
                1.0, static_cast<double>(view.model.size()) /
                         static_cast<double>(std::max<std::size_t>(view.sparse_model.size(), 1))))};
    const SceneIndex* index = &view.index;
    const PointCloud* points = &view.sparse_model;
    const Box* capture_box = hide_occluded ? &view.landmark.box : nullptr;
    const bool several_views = view.landmark.multi_view();
    return [=](const Eigen::Isometry3f& T) {
      return mean_surface_distance(*index, *points, T, capture_box,
                                   several_views ? &views : nullptr);
    };
  };
}

CoarseScoreFactory sensor_coarse_score() {
  return [](const CoarseView& view) -> CoarseScore {
    // The metric needs_empty_distances, so the search gives them; without, no probes.
    std::vector<Eigen::Vector3f> centres;
    std::vector<float> distances;
    if (view.empty_distances) {
      centres = thin(view.landmark.empty_space.centres(), 300);
      distances = thin(*view.empty_distances, 300);
    }
    const SceneIndex* index = &view.index;
    const Landmark* landmark = &view.landmark;
    const PointCloud* model = &view.model;
    const Eigen::Vector3f capture_sensor = view.landmark.sensor_origin.cast<float>();
    return [index, landmark, model, capture_sensor, centres = std::move(centres),
            distances = std::move(distances)](const Eigen::Isometry3f& T) {
      return sensor_fit(*index, *model, capture_sensor, T).mean_cost() +
             empty_space_penalty(*index, *landmark, centres, distances, T);
    };
  };
}

}  // namespace lmk::detail
