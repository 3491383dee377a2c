#include "landmark/find_landmark.h"

#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>

#include "geometry/error.h"
#include "geometry/filters.h"
#include "geometry/voxel_grid.h"
#include "landmark/detail/reference_search.h"
#include "landmark/non_max_suppression.h"

namespace lmk {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void check_settings(const FindSettings& s) {
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  const auto methods = search_methods();
  if (std::find(methods.begin(), methods.end(), s.method) == methods.end()) {
    std::string known;
    for (const auto& m : methods) known += (known.empty() ? "" : ", ") + m;
    throw Error("unknown search method '" + s.method + "' (known: " + known + ")");
  }
  find_error_metric(s.metric);  // throws for an unknown name
  if (!positive(s.leaf_size)) throw Error("find: leaf size must be positive and finite");
  if (!(s.sample_fraction > 0.0 && s.sample_fraction <= 1.0)) {
    throw Error("find: sample fraction must be in (0, 1]");
  }
  if (s.max_seeds == 0) throw Error("find: max seeds must be at least 1");
  if (s.icp_iterations < 1) throw Error("find: ICP iterations must be at least 1");
  if (!positive(s.nms_radius)) throw Error("find: NMS radius must be positive and finite");
  if (!(s.threshold > 0.0)) throw Error("find: threshold must be positive");
  if (s.threads < 0) throw Error("find: threads must be 0 (all cores) or more");
  if (s.work_volume && !s.work_volume->is_valid()) {
    throw Error("find: the work volume needs a finite pose and positive sides");
  }
}

// Steps 5 and 6: non-max suppression on box centres, then the error threshold.
std::vector<Match> select(std::vector<Match> candidates, const FindSettings& s,
                          SearchStats& stats) {
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> errors;
  for (const Match& m : candidates) {
    centres.push_back(m.box.center());
    errors.push_back(m.error);
  }
  const std::vector<std::size_t> kept = non_max_suppression(centres, errors, s.nms_radius);
  stats.after_nms = kept.size();
  std::vector<Match> matches;
  for (std::size_t i : kept) {
    if (candidates[i].error < s.threshold) matches.push_back(std::move(candidates[i]));
  }
  return matches;
}

}  // namespace

std::vector<std::string> search_methods() { return {"reference"}; }

FindResult find_landmark(const PointCloud& scene, const Landmark& landmark,
                         const FindSettings& settings) {
  check_settings(settings);
  landmark.validate("landmark '" + landmark.name + "'");
  const auto start = Clock::now();
  FindResult result;
  SearchStats& stats = result.stats;
  stats.scene_points = scene.count_finite();

  // Steps 1-2: crop to the work volume, voxel-downsample.
  const PointCloud cropped =
      settings.work_volume ? crop(scene, *settings.work_volume) : remove_non_finite(scene);
  if (cropped.empty()) {
    throw Error(settings.work_volume ? "find: the work volume holds no scene point"
                                     : "find: the scene holds no finite point");
  }
  const PointCloud points = voxel_downsample(cropped, settings.leaf_size);
  stats.scene_points_used = points.size();
  const KdTree scene_tree(points);
  const KdTree landmark_tree(landmark.points);

  // Step 3: seeded random sample of a fraction of the points, capped.
  const auto wanted = static_cast<std::size_t>(
      std::ceil(settings.sample_fraction * static_cast<double>(points.size())));
  const Indices seeds =
      random_sample_indices(points.size(), std::min(settings.max_seeds, wanted), settings.seed);
  stats.seeds = seeds.size();
  stats.seconds_preprocess = seconds_since(start);

  // Step 4, in an arena of the requested size: no process-wide thread setting.
  const auto search_start = Clock::now();
  const detail::SearchInput input{points,
                                  landmark,
                                  SceneView{points, scene_tree},
                                  LandmarkView{landmark.points, landmark_tree, landmark.box},
                                  seeds,
                                  find_error_metric(settings.metric),
                                  settings};
  std::vector<Match> candidates;
  tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
  arena.execute([&] { candidates = detail::reference_candidates(input); });
  for (const Match& m : candidates)
    stats.icp_iterations += static_cast<std::size_t>(m.icp_iterations);
  stats.seconds_search = seconds_since(search_start);

  const auto select_start = Clock::now();
  result.matches = select(std::move(candidates), settings, stats);
  if (settings.keep_aligned_points) {
    for (Match& m : result.matches) {
      m.aligned_points = landmark.points;
      for (auto& p : m.aligned_points.points) p = (m.T_scene_capture.cast<float>() * p);
      m.aligned_points.T_cloud_sensor = scene.T_cloud_sensor;
    }
  }
  stats.seconds_select = seconds_since(select_start);
  stats.seconds_total = seconds_since(start);
  return result;
}

}  // namespace lmk
