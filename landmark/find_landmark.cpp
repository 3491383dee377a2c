// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/find_landmark.h"

#include <tbb/task_arena.h>

#include <cmath>

#include "lmk/geometry/error.h"
#include "lmk/geometry/filters.h"
#include "lmk/geometry/voxel_grid.h"
#include "lmk/landmark/detail/fast_search.h"
#include "lmk/landmark/detail/point_pair_voting.h"
#include "lmk/landmark/detail/reference_search.h"
#include "lmk/landmark/detail/relief_seeds.h"
#include "lmk/landmark/detail/stopwatch.h"
#include "lmk/landmark/non_max_suppression.h"

namespace lmk {
namespace {

using detail::Clock;
using detail::seconds_since;

// Why a candidate was turned down, as Rejection::reason and describe_rejections say it.
constexpr const char* kRejectedError = "error above threshold";
constexpr const char* kRejectedCoverage = "coverage too low";
constexpr const char* kRejectedEmptySpace = "empty space occupied";
constexpr const char* kRejectedOverlap = "inside a better match";

// Steps 5 and 6: non-max suppression on box centres, then the error threshold (and, for metrics
// that measure them, the coverage and the empty space), then, with `suppress_overlaps` (the fast
// method's, not the paper's), the matches inside a better match's box (exclusive_boxes).
// Candidates turned down go to `rejected` with the first test they failed.
void select(std::vector<Match> candidates, const SelectionSettings& s, bool suppress_overlaps,
            FindResult& result) {
  SearchStats& stats = result.stats;
  const std::vector<std::size_t> kept = non_max_suppression_of(candidates, s.nms_radius);
  stats.after_nms = kept.size();
  const auto reject = [&](Match& m, std::size_t& count, const char* reason) {
    ++count;
    result.rejected.push_back({std::move(m), reason});
  };
  for (std::size_t i : kept) {
    Match& m = candidates[i];
    if (!(m.error < stats.threshold)) {
      reject(m, stats.rejected_error, kRejectedError);
    } else if (!std::isnan(m.terms.coverage) && m.terms.coverage < s.min_coverage) {
      reject(m, stats.rejected_coverage, kRejectedCoverage);
    } else if (m.terms.empty_space_probes > 0 &&
               static_cast<double>(m.terms.empty_space_violations) >
                   s.max_empty_space_violation * static_cast<double>(m.terms.empty_space_probes)) {
      reject(m, stats.rejected_empty_space, kRejectedEmptySpace);
    } else {
      result.matches.push_back(std::move(m));
    }
  }
  if (!suppress_overlaps) return;
  // The matches come best first (non_max_suppression's order).
  std::vector<Box> boxes;
  for (const Match& m : result.matches) boxes.push_back(m.box);
  std::vector<char> exclusive(boxes.size(), 0);
  for (std::size_t i : exclusive_boxes(boxes)) exclusive[i] = 1;
  std::vector<Match> accepted;
  for (std::size_t i = 0; i < result.matches.size(); ++i) {
    if (exclusive[i]) {
      accepted.push_back(std::move(result.matches[i]));
    } else {
      reject(result.matches[i], stats.rejected_overlap, kRejectedOverlap);
    }
  }
  result.matches = std::move(accepted);
}

// Steps 3 to 6 in an indexed scene, for inputs already checked.
FindResult search(const SceneIndex& index, const LandmarkIndex& prepared,
                  const FindSettings& settings) {
  std::string why;
  if (!prepared.suits(settings, &why)) throw Error("find: " + why);
  const Landmark& landmark = prepared.landmark();
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
  // Fast: seeds near relief only (detail/relief_seeds.h), in cells of half the landmark's size,
  // and as many as put seeds_per_instance on each instance-sized stretch of them.
  Indices seeds;
  if (fast) {
    const double diameter = prepared.diameter();
    detail::ReliefTest relief;
    relief.cell = 0.5 * diameter;
    relief.angle = detail::kCoplanarAngle;
    relief.T_cloud_sensor = index.T_scene_sensor();
    relief.noise = index.settings().depth_noise();
    const Indices candidates = detail::points_near_relief(points, relief);
    // One seed per cell of a grid whose cells an instance's surface (about as many coarse
    // leaves as the landmark has coarse points) spans seeds_per_instance times; coarser while the
    // seeds would exceed the cap.
    const double leaf = index.settings().coarse_leaf;
    double spacing = leaf * std::sqrt(std::max(1.0, static_cast<double>(prepared.coarse().size()) /
                                                        settings.fast.seeds_per_instance));
    const std::size_t cap = effective_max_seeds(settings);
    seeds = detail::spread_seeds(points, candidates, spacing, settings.sampling.seed);
    while (seeds.size() > cap) {
      spacing *= 1.02 * std::sqrt(static_cast<double>(seeds.size()) / static_cast<double>(cap));
      seeds = detail::spread_seeds(points, candidates, spacing, settings.sampling.seed);
    }
  } else {
    const auto wanted = static_cast<std::size_t>(
        std::ceil(settings.reference.sample_fraction * static_cast<double>(points.size())));
    seeds = random_sample_indices(points.size(), std::min(effective_max_seeds(settings), wanted),
                                  settings.sampling.seed);
  }
  stats.seeds = seeds.size();
  // The sensor metric tests empty space beyond the noise, which far away exceeds the landmark
  // distance field's band.
  LandmarkView landmark_view{landmark.points, prepared.tree(), landmark.box, landmark};
  if (metric.unit == ErrorMetric::Unit::sigma)
    landmark_view.empty_distances = &prepared.empty_distances();
  stats.seconds_preprocess = seconds_since(start);

  // Step 4, in an arena of the requested size: no process-wide thread setting.
  const auto search_start = Clock::now();
  const detail::SearchInput input{
      index,         points, landmark, prepared,        SceneView{index},
      landmark_view, seeds,  metric,   stats.threshold, settings};
  std::vector<Match> candidates;
  const int threads = settings.execution.threads;
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
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
  select(std::move(candidates), settings.selection, fast && settings.fast.suppress_overlaps,
         result);
  if (settings.execution.keep_aligned_points) {
    for (Match& m : result.matches) {
      m.aligned_points = landmark.points.transformed(m.T_scene_capture);
      m.aligned_points.T_cloud_sensor = index.T_scene_sensor();
    }
  }
  stats.seconds_select = seconds_since(select_start);
  stats.seconds_total = seconds_since(start);
  return result;
}

}  // namespace

std::string describe_rejections(const SearchStats& s) {
  if (s.after_nms == 0) {
    return "no candidate pose: nothing in the scene has the landmark's shape";
  }
  std::string out;
  const auto add = [&out](std::size_t n, const char* why) {
    if (n == 0) return;
    out += (out.empty() ? "rejected: " : ", ") + std::to_string(n) + " " + why;
  };
  add(s.rejected_error, kRejectedError);
  add(s.rejected_coverage, kRejectedCoverage);
  add(s.rejected_empty_space, kRejectedEmptySpace);
  add(s.rejected_overlap, kRejectedOverlap);
  return out;
}

FindResult find_landmark(const PointCloud& scene, const Landmark& landmark,
                         const FindSettings& settings) {
  // The landmark first: its errors (flat, invalid) come before the scene's.
  const LandmarkIndex prepared = LandmarkIndex::borrowing(landmark, settings);
  const SceneIndex index(scene, settings.scene);
  FindResult result = search(index, prepared, settings);
  const double built = index.seconds_to_build() + prepared.seconds_to_build();
  result.stats.seconds_preprocess += built;
  result.stats.seconds_total += built;
  result.stats.scene_points = scene.count_finite();
  return result;
}

FindResult find_landmark(const SceneIndex& index, const Landmark& landmark,
                         const FindSettings& settings) {
  const LandmarkIndex prepared = LandmarkIndex::borrowing(landmark, settings);
  FindResult result = search(index, prepared, settings);
  result.stats.seconds_preprocess += prepared.seconds_to_build();
  result.stats.seconds_total += prepared.seconds_to_build();
  return result;
}

FindResult find_landmark(const SceneIndex& index, const LandmarkIndex& landmark,
                         const FindSettings& settings) {
  validate(settings);
  return search(index, landmark, settings);
}

}  // namespace lmk
