// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/find_landmark.h"

#include <tbb/parallel_invoke.h>

#include <cmath>
#include <functional>
#include <memory>

#include "lmk/geometry/error.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/geometry/voxel_grid.h"
#include "lmk/geometry/worker_threads.h"
#include "lmk/search/confidence/competitor.h"
#include "lmk/search/confidence/confidence_calibration.h"
#include "lmk/search/confidence/view_determinacy.h"
#include "lmk/search/detail/selection_tests.h"
#include "lmk/search/metrics/colour_term.h"
#include "lmk/search/non_max_suppression.h"
#include "lmk/search/search_method.h"

namespace lmk {
namespace {

// Steps 5 and 6: non-max suppression on box centres, then the error threshold (and, for metrics
// that measure them, the coverage and the empty space), then, with `suppress_overlaps` (the fast
// method's, not the paper's), the matches inside a better match's box (exclusive_boxes).
// Candidates turned down go to `rejected` with the first test they failed; with `keep_suppressed`,
// those non-max suppression removed go to `suppressed`.
void select(std::vector<Match> candidates, const SelectionSettings& s, bool suppress_overlaps,
            bool keep_suppressed, const std::function<bool(const Match&)>& undetermined,
            FindResult& result) {
  SearchStats& stats = result.stats;
  const std::vector<std::size_t> kept = non_max_suppression_of(candidates, s.nms_radius);
  stats.after_nms = kept.size();
  if (keep_suppressed) {
    std::vector<char> is_kept(candidates.size(), 0);
    for (std::size_t i : kept) is_kept[i] = 1;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      if (!is_kept[i])
        result.suppressed.push_back({candidates[i], RejectionReason::suppressed_by_a_better_match});
    }
  }
  const auto reject = [&](Match& m, RejectionReason reason) {
    stats.rejected.add(reason);
    result.rejected.push_back({std::move(m), reason});
  };
  for (std::size_t i : kept) {
    Match& m = candidates[i];
    if (!(m.error < stats.threshold)) {
      // Over only by the colour term: the shape matched, the colour did not.
      const double colour_penalty = m.terms.colour ? m.terms.colour->penalty : 0.0;
      const bool shape_fits = m.error - colour_penalty < stats.threshold;
      if (colour_penalty > 0.0 && shape_fits) {
        reject(m, RejectionReason::colour_differs);
      } else {
        reject(m, RejectionReason::error_above_threshold);
      }
    } else if (detail::coverage_too_low(m.terms, s)) {
      reject(m, RejectionReason::coverage_too_low);
    } else if (detail::empty_space_occupied(m.terms, s)) {
      reject(m, RejectionReason::empty_space_occupied);
    } else if (undetermined(m)) {
      reject(m, RejectionReason::too_little_shown);
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
      reject(result.matches[i], RejectionReason::inside_a_better_match);
    }
  }
  result.matches = std::move(accepted);
}

// What a search of `prepared` in `index` works with once its settings are resolved: the metric
// and the landmark's view of it.
struct Prepared {
  /// lmk::Error when `prepared` was built for other settings (LandmarkIndex::suits()).
  Prepared(const SceneIndex& index, const LandmarkIndex& prepared, const FindSettings& requested)
      : settings(suited(requested, prepared).resolved()),
        method(detail::search_method_steps(settings.method)),
        metric(detail::with_colour_term(find_error_metric(settings.selection.metric), settings,
                                        prepared.landmark(), index)),
        landmark(prepared.landmark()),
        view{landmark.points, prepared.tree(), landmark.box, landmark},
        calibration(
            calibration_for(settings.selection.metric, settings.selection.calibration.get())) {
    if (metric.needs_empty_distances) view.empty_distances = &prepared.empty_distances();
  }

  static const FindSettings& suited(const FindSettings& requested, const LandmarkIndex& prepared) {
    std::string why;
    if (!prepared.suits(requested, &why)) throw Error("find: " + why);
    return requested;
  }

  // What every search's statistics start from: the method, metric and threshold it applies, and
  // the scene's points.
  SearchStats initial_stats(const SceneIndex& index) const {
    SearchStats s;
    s.method = settings.method;
    s.metric = settings.selection.metric;
    s.threshold = *settings.selection.threshold;
    s.scene_points = index.input_points();
    return s;
  }

  // The confidence of each match (match_confidence.h), against every candidate in `pool`; those
  // below the cut are turned down.
  void assess(const SceneIndex& index, const LandmarkIndex& prepared,
              const std::vector<Match>& pool, FindResult& result) const {
    if (result.matches.empty()) return;
    PointCloud storage;
    const PointCloud& coarse = method.coarse_landmark(prepared, index, storage);
    const std::optional<Eigen::Vector3d> flat =
        flat_normal(landmark.points, index.settings().leaf_size);
    const detail::ConfidenceInput input{index,
                                        landmark,
                                        coarse,
                                        prepared.tree(),
                                        metric,
                                        view,
                                        settings.selection,
                                        calibration,
                                        flat,
                                        flat ? &prepared.empty_distances() : nullptr};
    std::vector<const Match*> rivals;
    for (const Match& m : pool) rivals.push_back(&m);
    std::vector<Match> kept;
    for (Match& m : result.matches) {
      m.confidence = detail::assess_match(input, m, rivals);
      if (!passes_confidence(m.confidence.probability, settings.selection.min_confidence)) {
        result.stats.rejected.add(RejectionReason::confidence_too_low);
        result.rejected.push_back({std::move(m), RejectionReason::confidence_too_low});
      } else {
        kept.push_back(std::move(m));
      }
    }
    result.matches = std::move(kept);
  }

  // What the method gets for `seeds` (indices into its seed cloud; none to align at a pose) and
  // its own scene work (none: it makes what it needs).
  detail::SearchInput input(const SceneIndex& index, const LandmarkIndex& prepared,
                            const Indices& seeds,
                            const detail::MethodScene* method_scene = nullptr) const {
    return {
        index,  method.seed_cloud(index),      landmark, prepared,    SceneView{index}, view, seeds,
        metric, *settings.selection.threshold, settings, method_scene};
  }

  const FindSettings settings;  ///< resolved: what follows reads plain fields
  const detail::SearchMethodSteps& method;
  const ErrorMetric metric;  ///< with the colour term when the search weighs colour
  const Landmark& landmark;
  LandmarkView view;
  const ConfidenceCalibration* calibration;  ///< null: none fitted for the metric
};

// Steps 5 and 6 for the scored candidates, and their confidence: what the search and
// find_near_pose select by.
void select_and_assess(const SceneIndex& index, const LandmarkIndex& prepared, const Prepared& p,
                       detail::CandidateSet candidates, bool suppress_overlaps,
                       FindResult& result) {
  // Every candidate scored is a rival of the matches (their confidence): keep them before
  // selection moves them.
  std::vector<Match> pool = candidates.kept;
  pool.insert(pool.end(), candidates.suppressed.begin(), candidates.suppressed.end());
  if (p.settings.execution.keep_suppressed) {
    for (Match& m : candidates.suppressed)
      result.suppressed.push_back({std::move(m), RejectionReason::suppressed_by_a_better_match});
  }
  select(
      std::move(candidates.kept), p.settings.selection, suppress_overlaps,
      p.settings.execution.keep_suppressed,
      [&](const Match& m) {
        return detail::shows_too_little_to_fix(index, p.landmark, m.T_scene_capture);
      },
      result);
  p.assess(index, prepared, pool, result);
}

// The method's alignment started at `T_scene_capture` (step 4 for one candidate), after the
// checks every entry point makes.
Match align_at(const SceneIndex& index, const LandmarkIndex& prepared, const Prepared& p,
               const Eigen::Isometry3d& T_scene_capture) {
  if (!T_scene_capture.matrix().allFinite()) throw Error("score pose: the pose is not finite");
  const Indices no_seeds;
  return p.method.align_at(p.input(index, prepared, no_seeds), T_scene_capture);
}

// Steps 3 to 6 in an indexed scene, for inputs already checked.
FindResult search(const SceneIndex& index, const LandmarkIndex& prepared,
                  const FindSettings& requested) {
  const Stopwatch total;
  Stopwatch stage;
  const Prepared p(index, prepared, requested);
  const FindSettings& settings = p.settings;
  const detail::SearchMethodSteps& method = p.method;
  FindResult result;
  result.stats = p.initial_stats(index);
  SearchStats& stats = result.stats;

  // Seeds: the points the method starts from (step 3), chosen beside the method's own work on the
  // scene: both read the index alone, and each is mostly serial (about a millisecond apiece on a
  // Kinect frame).
  const PointCloud& points = method.seed_cloud(index);
  stats.scene_points_used = points.size();
  Indices seeds;
  std::unique_ptr<const detail::MethodScene> method_scene;
  tbb::parallel_invoke([&] { seeds = method.seeds(index, prepared, settings); },
                       [&] { method_scene = method.prepare_scene(index, prepared); });
  stats.seeds = seeds.size();
  stats.seconds_preprocess = stage.seconds();

  // Step 4.
  stage.restart();
  detail::CandidateSet candidates =
      method.candidates(p.input(index, prepared, seeds, method_scene.get()), stats);
  for (const Match& m : candidates.kept)
    stats.icp_iterations += static_cast<std::size_t>(m.icp_iterations);
  stats.seconds_search = stage.seconds();

  stage.restart();
  select_and_assess(index, prepared, p, std::move(candidates), method.suppresses_overlaps(settings),
                    result);
  if (settings.execution.keep_aligned_points) {
    for (Match& m : result.matches) {
      m.aligned_points = p.landmark.points.transformed(m.T_scene_capture);
      m.aligned_points.T_cloud_sensor = index.T_scene_sensor();
    }
  }
  stats.seconds_select = stage.seconds();
  stats.seconds_total = total.seconds();
  return result;
}

}  // namespace

// Each call runs on the requested threads (with_worker_threads), its indexing included: two
// searches of one thread each, from two threads of the caller, share no worker.
FindResult find_landmark(const PointCloud& scene, const Landmark& landmark,
                         const FindSettings& settings) {
  validate(settings);
  FindResult result;
  with_worker_threads(settings.execution.threads, [&] {
    // The landmark first: its errors (flat, invalid) come before the scene's.
    const LandmarkIndex prepared = LandmarkIndex::borrowing(landmark, settings);
    const SceneIndex index(scene, settings.scene, settings.execution.stop);
    result = search(index, prepared, settings);
    const double built = index.seconds_to_build() + prepared.seconds_to_build();
    result.stats.seconds_preprocess += built;
    result.stats.seconds_total += built;
    result.stats.scene_points = scene.count_finite();
  });
  return result;
}

FindResult find_landmark(const SceneIndex& index, const Landmark& landmark,
                         const FindSettings& settings) {
  validate(settings);
  FindResult result;
  with_worker_threads(settings.execution.threads, [&] {
    const LandmarkIndex prepared = LandmarkIndex::borrowing(landmark, settings);
    result = search(index, prepared, settings);
    result.stats.seconds_preprocess += prepared.seconds_to_build();
    result.stats.seconds_total += prepared.seconds_to_build();
  });
  return result;
}

FindResult find_landmark(const SceneIndex& index, const LandmarkIndex& landmark,
                         const FindSettings& settings) {
  validate(settings);
  FindResult result;
  with_worker_threads(settings.execution.threads,
                      [&] { result = search(index, landmark, settings); });
  return result;
}

Match score_pose(const SceneIndex& index, const LandmarkIndex& prepared,
                 const FindSettings& requested, const Eigen::Isometry3d& T_scene_capture) {
  validate(requested);
  const Prepared p(index, prepared, requested);
  return align_at(index, prepared, p, T_scene_capture);
}

FindResult find_near_pose(const SceneIndex& index, const LandmarkIndex& prepared,
                          const FindSettings& requested, const Eigen::Isometry3d& T_predicted) {
  validate(requested);
  const Stopwatch total;
  const Prepared p(index, prepared, requested);
  FindResult result;
  result.stats = p.initial_stats(index);
  with_worker_threads(requested.execution.threads, [&] {
    detail::CandidateSet candidates;
    candidates.kept.push_back(align_at(index, prepared, p, T_predicted));
    select_and_assess(index, prepared, p, std::move(candidates), false, result);
  });
  result.stats.seconds_total = total.seconds();
  return result;
}

}  // namespace lmk
