#include "landmark/find_landmark.h"

#include <tbb/task_arena.h>

#include <cmath>

#include "geometry/error.h"
#include "geometry/filters.h"
#include "geometry/voxel_grid.h"
#include "landmark/detail/fast_search.h"
#include "landmark/detail/point_pair_voting.h"
#include "landmark/detail/reference_search.h"
#include "landmark/detail/relief_seeds.h"
#include "landmark/detail/stopwatch.h"
#include "landmark/non_max_suppression.h"

namespace lmk {
namespace {

using detail::Clock;
using detail::seconds_since;

void check_settings(const FindSettings& s) {
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  const auto methods = search_methods();
  if (std::find(methods.begin(), methods.end(), s.method) == methods.end()) {
    std::string known;
    for (const auto& m : methods) known += (known.empty() ? "" : ", ") + m;
    throw Error("unknown search method '" + s.method + "' (known: " + known + ")");
  }
  if (!s.metric.empty()) find_error_metric(s.metric);  // throws for an unknown name
  if (!positive(s.leaf_size)) throw Error("find: leaf size must be positive and finite");
  if (!positive(s.coarse_leaf)) throw Error("find: coarse leaf must be positive and finite");
  if (s.orientations != "upright" && s.orientations != "full") {
    throw Error("find: orientations must be 'upright' or 'full', not '" + s.orientations + "'");
  }
  if (!(s.max_tilt >= 0.0) || !std::isfinite(s.max_tilt)) {
    throw Error("find: the maximum tilt must be finite and non-negative");
  }
  if (!(s.min_coverage >= 0.0 && s.min_coverage <= 1.0)) {
    throw Error("find: the minimum coverage must be in [0, 1]");
  }
  if (!(s.max_empty_space_violation >= 0.0 && s.max_empty_space_violation <= 1.0)) {
    throw Error("find: the empty-space violation allowance must be in [0, 1]");
  }
  if (s.poses_per_seed < 1 || s.max_candidates == 0 || s.max_refined == 0) {
    throw Error("find: poses per seed, candidates and refined candidates must be at least 1");
  }
  if (!(s.prune_error > 0.0)) throw Error("find: the prune error must be positive");
  if (!(s.sample_fraction > 0.0 && s.sample_fraction <= 1.0)) {
    throw Error("find: sample fraction must be in (0, 1]");
  }
  if (s.max_seeds && *s.max_seeds == 0) throw Error("find: max seeds must be at least 1");
  if (!(s.seeds_per_instance >= 1.0) || !std::isfinite(s.seeds_per_instance)) {
    throw Error("find: seeds per instance must be finite and at least 1");
  }
  if (s.icp_iterations < 1) throw Error("find: ICP iterations must be at least 1");
  if (!positive(s.nms_radius)) throw Error("find: NMS radius must be positive and finite");
  if (s.threshold && !(*s.threshold > 0.0)) throw Error("find: threshold must be positive");
  if (s.threads < 0) throw Error("find: threads must be 0 (all cores) or more");
  if (s.work_volume && !s.work_volume->is_valid()) {
    throw Error("find: the work volume needs a finite pose and positive sides");
  }
}

// Steps 5 and 6: non-max suppression on box centres, then the error threshold (and, for metrics
// that measure them, the coverage and the empty space).
std::vector<Match> select(std::vector<Match> candidates, const FindSettings& s,
                          SearchStats& stats) {
  const std::vector<std::size_t> kept = non_max_suppression_of(candidates, s.nms_radius);
  stats.after_nms = kept.size();
  std::vector<Match> matches;
  for (std::size_t i : kept) {
    const Match& m = candidates[i];
    if (!(m.error < stats.threshold)) {
      ++stats.rejected_error;
      continue;
    }
    if (!std::isnan(m.terms.coverage) && m.terms.coverage < s.min_coverage) {
      ++stats.rejected_coverage;
      continue;
    }
    if (m.terms.empty_space_probes > 0 &&
        static_cast<double>(m.terms.empty_space_violations) >
            s.max_empty_space_violation * static_cast<double>(m.terms.empty_space_probes)) {
      ++stats.rejected_empty_space;
      continue;
    }
    matches.push_back(std::move(candidates[i]));
  }
  return matches;
}

// Steps 3 to 6 in an indexed scene, for inputs already checked.
FindResult search(const SceneIndex& index, const Landmark& landmark, const FindSettings& settings) {
  const auto start = Clock::now();
  FindResult result;
  SearchStats& stats = result.stats;
  const bool fast = settings.method == "fast";
  stats.method = settings.method;
  stats.metric = effective_metric(settings);
  const ErrorMetric& metric = find_error_metric(stats.metric);
  stats.threshold = effective_threshold(settings);
  stats.scene_points = index.input_points();

  // Seeds: a seeded random sample of the points the method starts from (step 3).
  const PointCloud& points = fast ? index.coarse() : index.fine();
  stats.scene_points_used = points.size();
  // Fast: the landmark at the scene's coarse leaf, which also sets the seed count.
  const PointCloud landmark_coarse =
      fast ? voxel_downsample(landmark.points, index.settings().coarse_leaf) : PointCloud();
  // Fast: seeds near relief only (detail/relief_seeds.h), in cells of half the landmark's size,
  // and as many as put seeds_per_instance on each instance-sized stretch of them.
  Indices seeds;
  if (fast) {
    const double diameter =
        std::max(static_cast<double>(landmark.points.bounds().diagonal().norm()),
                 3.0 * index.settings().coarse_leaf);
    const Indices candidates =
        detail::points_near_relief(points, 0.5 * diameter, detail::kCoplanarAngle);
    const auto wanted = static_cast<std::size_t>(
        std::ceil(settings.seeds_per_instance * static_cast<double>(candidates.size()) /
                  static_cast<double>(landmark_coarse.size())));
    for (Index k : random_sample_indices(
             candidates.size(), std::min(effective_max_seeds(settings), wanted), settings.seed)) {
      seeds.push_back(candidates[k]);
    }
  } else {
    const auto wanted = static_cast<std::size_t>(
        std::ceil(settings.sample_fraction * static_cast<double>(points.size())));
    seeds = random_sample_indices(points.size(), std::min(effective_max_seeds(settings), wanted),
                                  settings.seed);
  }
  stats.seeds = seeds.size();
  const KdTree landmark_tree(landmark.points);
  stats.seconds_preprocess = seconds_since(start);

  // Step 4, in an arena of the requested size: no process-wide thread setting.
  const auto search_start = Clock::now();
  const detail::SearchInput input{
      index,
      points,
      landmark,
      landmark_coarse,
      SceneView{index},
      LandmarkView{landmark.points, landmark_tree, landmark.box, landmark},
      seeds,
      metric,
      stats.threshold,
      settings};
  std::vector<Match> candidates;
  tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    if (fast) {
      detail::FastSearchStats fast_stats;
      candidates = detail::fast_candidates(input, fast_stats);
      stats.poses = fast_stats.poses;
      stats.clusters = fast_stats.clusters;
      stats.refined = fast_stats.refined;
      stats.seconds_vote = fast_stats.seconds_vote;
      stats.seconds_coarse = fast_stats.seconds_coarse;
      stats.seconds_fine = fast_stats.seconds_fine;
    } else {
      candidates = detail::reference_candidates(input);
    }
  });
  for (const Match& m : candidates)
    stats.icp_iterations += static_cast<std::size_t>(m.icp_iterations);
  stats.seconds_search = seconds_since(search_start);

  const auto select_start = Clock::now();
  result.matches = select(std::move(candidates), settings, stats);
  if (settings.keep_aligned_points) {
    for (Match& m : result.matches) {
      m.aligned_points = landmark.points.transformed(m.T_scene_capture);
      m.aligned_points.T_cloud_sensor = index.T_scene_sensor();
    }
  }
  stats.seconds_select = seconds_since(select_start);
  stats.seconds_total = seconds_since(start);
  return result;
}

void check_inputs(const FindSettings& settings, const Landmark& landmark) {
  check_settings(settings);
  const std::string what = "landmark '" + landmark.name + "'";
  landmark.validate(what);
  if (const auto why = degenerate_shape(landmark.points, landmark.settings.leaf_size, what,
                                        landmark.settings.allow_flat)) {
    throw Error(*why);
  }
}

}  // namespace

std::vector<std::string> search_methods() { return {"fast", "reference"}; }

std::size_t effective_max_seeds(const FindSettings& settings) {
  if (settings.max_seeds) return *settings.max_seeds;
  return settings.method == "reference" ? 1000 : 2000;
}

std::string describe_rejections(const SearchStats& s) {
  if (s.after_nms == 0) {
    return "no candidate pose: nothing in the scene has the landmark's shape";
  }
  std::string out;
  const auto add = [&out](std::size_t n, const char* why) {
    if (n == 0) return;
    out += (out.empty() ? "rejected: " : ", ") + std::to_string(n) + " " + why;
  };
  add(s.rejected_error, "error above threshold");
  add(s.rejected_coverage, "coverage too low");
  add(s.rejected_empty_space, "empty space occupied");
  return out;
}

SceneSettings scene_settings(const FindSettings& s) {
  SceneSettings scene;
  scene.work_volume = s.work_volume;
  scene.leaf_size = s.leaf_size;
  scene.coarse_leaf = std::max(s.coarse_leaf, s.leaf_size);
  scene.field_band = 2.0 * scene.coarse_leaf;
  scene.up = s.up;
  scene.base_frame = s.base_frame;
  return scene;
}

FindResult find_landmark(const PointCloud& scene, const Landmark& landmark,
                         const FindSettings& settings) {
  check_inputs(settings, landmark);
  const SceneIndex index(scene, scene_settings(settings));
  FindResult result = search(index, landmark, settings);
  result.stats.seconds_preprocess += index.seconds_to_build();
  result.stats.seconds_total += index.seconds_to_build();
  result.stats.scene_points = scene.count_finite();
  return result;
}

FindResult find_landmark(const SceneIndex& index, const Landmark& landmark,
                         const FindSettings& settings) {
  check_inputs(settings, landmark);
  return search(index, landmark, settings);
}

std::string effective_metric(const FindSettings& settings) {
  if (!settings.metric.empty()) return settings.metric;
  return settings.method == "fast" ? "visibility" : "paper";
}

double effective_threshold(const FindSettings& settings) {
  return settings.threshold ? *settings.threshold
                            : find_error_metric(effective_metric(settings)).default_threshold;
}

}  // namespace lmk
