// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/evaluation.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <memory>
#include <mutex>

#include "lmk/eval/detail/pair_cache.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/hash.h"
#include "lmk/geometry/statistics.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/geometry/version.h"
#include "lmk/geometry/worker_threads.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/search/capture_check.h"
#include "lmk/search/confidence/confidence_calibration.h"
#include "lmk/search/internal/find_settings_json.h"
#include "lmk/search/metrics/error_metrics.h"

namespace lmk {

namespace fs = std::filesystem;

namespace {

// Matches are kept up to this multiple of the larger of the threshold and the metric's default,
// for the curve against the threshold; every threshold up to the default then shares one search.
constexpr double kRecordedThresholdFactor = 2.0;

// For resolved settings.
double recorded_threshold(const FindSettings& find) {
  return kRecordedThresholdFactor *
         std::max(*find.selection.threshold,
                  find_error_metric(find.selection.metric).default_threshold);
}

// Each landmark's index, built by the first pair that searches it (a run whose pairs are all cached
// builds none) and shared by the rest, its build time shared out among them like a scene's.
class LandmarkIndexes {
 public:
  LandmarkIndexes(const std::vector<Landmark>& landmarks, const FindSettings& find)
      : landmarks_(landmarks), find_(find), built_(landmarks.size()), once_(landmarks.size()) {}
  const LandmarkIndex& operator[](std::size_t k) {
    std::call_once(once_[k], [&] {
      built_[k] = std::make_unique<LandmarkIndex>(LandmarkIndex::borrowing(landmarks_[k], find_));
    });
    return *built_[k];
  }

 private:
  const std::vector<Landmark>& landmarks_;
  FindSettings find_;
  std::vector<std::unique_ptr<LandmarkIndex>> built_;
  std::deque<std::once_flag> once_;
};

PairResult search_pair(const SceneIndex& index, const DatasetScene& scene,
                       const LandmarkIndex& landmark, const DatasetLandmark& entry,
                       const DatasetPair& truth, const FindSettings& find) {
  PairResult r;
  r.scene = scene.name;
  r.landmark = entry.name;
  r.setting = scene.setting;
  r.in_context = truth.in_context;
  r.symmetry = entry.symmetry;
  r.truth = truth.instances;
  r.truth_hidden = truth.hidden;
  const FindResult found = find_landmark(index, landmark, pair_search(find, scene));
  for (const Match& m : found.matches) r.found.push_back({m.box, m.error, m.terms, m.confidence});
  r.seconds = found.stats.seconds_total;
  r.seeds = found.stats.seeds;
  r.rejections = describe_rejections(found.stats);
  r.sensor_position = scene.T_scene_sensor.translation();
  return r;
}

}  // namespace

FindSettings pair_search(const FindSettings& find, const DatasetScene& scene) {
  FindSettings f = find;
  f.execution = ExecutionSettings();
  f.execution.threads = 1;
  f.selection.threshold = recorded_threshold(find);
  // Every match is kept whatever its confidence: the evaluation applies the cut afterwards, as it
  // does the threshold, so that one search serves the risk-coverage curve.
  f.selection.min_confidence = 0.0;
  if (scene.up) f.scene.up = scene.up;
  return f;
}

PairInput matches_within(const PairResult& pair, double threshold, double min_confidence) {
  PairInput in;
  in.truth = pair.truth;
  in.symmetry = pair.symmetry;
  in.in_context = pair.in_context;
  for (double hidden : pair.truth_hidden) in.ignored.push_back(hidden >= kIgnoredHiddenFraction);
  for (const FoundBox& f : pair.found) {
    if (f.error < threshold && passes_confidence(f.confidence.probability, min_confidence))
      in.found.push_back(f.box.pose);
  }
  return in;
}

std::string evaluation_cache_key(const FindSettings& find, const std::string& fingerprint) {
  // The settings as the search applies them, so that spelling out a default keeps the key.
  FindSettings applied = find.resolved();
  applied.selection.threshold = recorded_threshold(applied);
  applied.selection.min_confidence = 0.0;  // applied afterwards (pair_search)
  const nlohmann::json settings = detail::result_settings_to_json(applied);
  return Fnv1a()
      .add(settings.dump())
      .add(fingerprint)
      .add(kVersion)
      .add_value(kSearchRevision)
      .hex();
}

std::string default_cache_dir() {
  if (const char* dir = std::getenv("LMK_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return (fs::path(xdg) / "lmk").string();
  if (const char* home = std::getenv("HOME"); home && *home)
    return (fs::path(home) / ".cache" / "lmk").string();
  return ".lmk-cache";
}

namespace {

// A pair to search: a scene and a landmark of the dataset, by index.
struct PairJob {
  std::size_t scene, landmark;
};

// Every pair the settings ask for (in context only, this shard's only), scene by scene.
std::vector<PairJob> pair_jobs(const Dataset& dataset, const EvaluationSettings& settings) {
  std::vector<PairJob> jobs;
  for (std::size_t s = 0; s < dataset.scenes.size(); ++s) {
    for (std::size_t l = 0; l < dataset.landmarks.size(); ++l) {
      const DatasetPair truth = dataset.pair(dataset.scenes[s], dataset.landmarks[l].name);
      if (settings.in_context_only && !truth.in_context) continue;
      if (settings.shard && pair_shard(dataset.scenes[s].name, dataset.landmarks[l].name,
                                       settings.shard->count) != settings.shard->index) {
        continue;
      }
      jobs.push_back({s, l});
    }
  }
  return jobs;
}

// The jobs' ranges [first, last), one per scene.
std::vector<std::pair<std::size_t, std::size_t>> jobs_by_scene(const std::vector<PairJob>& jobs) {
  std::vector<std::pair<std::size_t, std::size_t>> ranges;
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    if (ranges.empty() || jobs[ranges.back().first].scene != jobs[k].scene)
      ranges.push_back({k, k});
    ranges.back().second = k + 1;
  }
  return ranges;
}

// The searches of an evaluation: each scene's pairs from the cache, or searched and cached, into
// `pairs` (one slot per job); scenes in parallel, and each scene's pairs in parallel.
class PairSearches {
 public:
  PairSearches(const std::string& dir, const Dataset& dataset, const std::vector<PairJob>& jobs,
               const EvaluationSettings& settings, const FindSettings& find,
               LandmarkIndexes& landmarks, const detail::PairCache& cache)
      : dir_(dir),
        dataset_(dataset),
        jobs_(jobs),
        settings_(settings),
        find_(find),
        landmarks_(landmarks),
        cache_(cache),
        jobs_per_landmark_(dataset.landmarks.size(), 0),
        missing_(jobs.size(), 0) {
    for (const PairJob& job : jobs) ++jobs_per_landmark_[job.landmark];
  }

  // Fills `pairs`; Interrupted when the settings' stop_requested said so.
  void run(std::vector<PairResult>& pairs) {
    pairs.resize(jobs_.size());
    const auto ranges = jobs_by_scene(jobs_);
    with_worker_threads(settings_.threads, [&] {
      tbb::parallel_for(std::size_t{0}, ranges.size(), [&](std::size_t s) {
        run_scene(ranges[s].first, ranges[s].second, pairs);
      });
    });
    if (stopped_) {
      throw Interrupted("interrupted after " + std::to_string(done_) + " of " +
                        std::to_string(jobs_.size()) + " pairs; " +
                        (settings_.cache_dir.empty() ? "nothing is kept without a cache"
                                                     : "they are cached in " + settings_.cache_dir +
                                                           ": the same command resumes from them"));
    }
  }

  /// Per job: whether it was neither cached nor searched (cached_only: a merge's missing pair).
  const std::vector<char>& missing() const { return missing_; }

 private:
  // A scene's jobs [first, last): read from the cache, and only when one is not there is the
  // scene read, once.
  void run_scene(std::size_t first, std::size_t last, std::vector<PairResult>& pairs) {
    const DatasetScene& scene = dataset_.scenes[jobs_[first].scene];
    std::vector<std::size_t> to_search;
    for (std::size_t k = first; k < last; ++k) {
      const std::string& name = dataset_.landmarks[jobs_[k].landmark].name;
      if (auto hit = cache_.read(scene.name, name)) {
        pairs[k] = std::move(*hit);
        finished(true);
      } else {
        to_search.push_back(k);
      }
    }
    if (settings_.cached_only) {
      for (std::size_t k : to_search) missing_[k] = 1;
      return;
    }
    if (to_search.empty() || stopping()) return;
    search_scene(scene, to_search, pairs);
  }

  // The scene is indexed once for all of its landmarks (steps 1-2 of the search), as each
  // landmark is for all of its scenes, and the indexes' build times are shared out among the
  // pairs that use them.
  void search_scene(const DatasetScene& scene, const std::vector<std::size_t>& to_search,
                    std::vector<PairResult>& pairs) {
    const PointCloud cloud = read_cloud((fs::path(dir_) / scene.file).string());
    const SceneIndex index(cloud, pair_search(find_, scene).scene);
    const double index_share = index.seconds_to_build() / static_cast<double>(to_search.size());
    const double threshold = *find_.selection.threshold;
    tbb::parallel_for(std::size_t{0}, to_search.size(), [&](std::size_t i) {
      if (stopping()) return;
      const std::size_t k = to_search[i];
      const DatasetLandmark& entry = dataset_.landmarks[jobs_[k].landmark];
      const LandmarkIndex& landmark = landmarks_[jobs_[k].landmark];
      PairResult searched =
          search_pair(index, scene, landmark, entry, dataset_.pair(scene, entry.name), find_);
      searched.seconds +=
          index_share +
          landmark.seconds_to_build() / static_cast<double>(jobs_per_landmark_[jobs_[k].landmark]);
      // Kept as the cache holds it, so that a fresh result and a resumed one agree.
      pairs[k] = cache_.store(searched, threshold, settings_.tolerance);
      finished(false);
    });
  }

  bool stopping() {
    if (!stopped_ && settings_.stop_requested && settings_.stop_requested()) stopped_ = true;
    return stopped_.load();
  }

  void finished(bool from_cache) {
    const std::size_t c = from_cache ? ++cached_ : cached_.load();
    const std::size_t d = ++done_;
    if (settings_.progress) settings_.progress(d, jobs_.size(), c);
  }

  const std::string& dir_;
  const Dataset& dataset_;
  const std::vector<PairJob>& jobs_;
  const EvaluationSettings& settings_;
  const FindSettings& find_;
  LandmarkIndexes& landmarks_;
  const detail::PairCache& cache_;
  std::vector<std::size_t> jobs_per_landmark_;
  std::vector<char> missing_;
  std::atomic<std::size_t> done_{0}, cached_{0};
  std::atomic<bool> stopped_{false};
};

// What each pair's landmark says of its demonstration, cached or not: where it was seen from
// (--by views), its up axis, capture box and, where the dataset gives none and the settings ask
// for it, the symmetry its capture found.
void add_landmark_context(std::vector<PairResult>& pairs, const std::vector<PairJob>& jobs,
                          const std::vector<Landmark>& landmarks, bool with_capture_symmetry) {
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    const Landmark& l = landmarks[jobs[k].landmark];
    PairResult& p = pairs[k];
    p.view_origins =
        l.multi_view() ? l.view_origins : std::vector<Eigen::Vector3d>{l.sensor_origin};
    p.landmark_up = l.up;
    p.capture_box = l.box.pose;
    p.landmark_size = l.box.size.norm();
    if (!with_capture_symmetry || p.symmetry.axis) continue;
    if (const std::optional<Symmetry> found = capture_symmetry(l)) {
      p.symmetry = *found;
      p.symmetry_from_capture = true;
    }
  }
}

// The pairs not missing, in job order; the missing ones named in `evaluation.missing`.
std::vector<PairResult> kept_pairs(Evaluation& evaluation, const Dataset& dataset,
                                   const std::vector<PairJob>& jobs,
                                   const std::vector<char>& missing) {
  std::vector<PairResult> kept;
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    if (!missing[k]) {
      kept.push_back(std::move(evaluation.pairs[k]));
    } else {
      evaluation.missing.emplace_back(dataset.scenes[jobs[k].scene].name,
                                      dataset.landmarks[jobs[k].landmark].name);
    }
  }
  return kept;
}

}  // namespace

Evaluation evaluate(const std::string& dir, const Dataset& dataset,
                    const EvaluationSettings& settings) {
  const Stopwatch stopwatch;
  Evaluation evaluation;
  evaluation.dataset = dataset.name;
  validate(settings.find);  // bad settings fail before any work
  check_worker_threads(settings.threads, "eval: threads (--threads)");
  evaluation.settings = settings;
  evaluation.settings.find = settings.find.resolved();
  evaluation.settings.progress = nullptr;
  evaluation.settings.stop_requested = nullptr;
  const FindSettings& find = evaluation.settings.find;
  if (settings.cached_only && settings.cache_dir.empty()) {
    throw Error("merge: the pairs come from the cache, and there is none (--no-cache)");
  }

  // Every pair to search, scene by scene, and the landmarks, loaded once.
  const std::vector<PairJob> jobs = pair_jobs(dataset, settings);
  std::vector<Landmark> landmarks;
  for (const DatasetLandmark& entry : dataset.landmarks)
    landmarks.push_back(load_landmark((fs::path(dir) / entry.file).string()));
  LandmarkIndexes landmark_indexes(landmarks, pair_search(find, DatasetScene()));
  evaluation.fingerprint = dataset_fingerprint(dir, dataset, landmarks);
  const detail::PairCache cache(settings.cache_dir,
                                evaluation_cache_key(find, evaluation.fingerprint));

  PairSearches searches(dir, dataset, jobs, settings, find, landmark_indexes, cache);
  searches.run(evaluation.pairs);
  add_landmark_context(evaluation.pairs, jobs, landmarks, settings.capture_symmetry);
  // Confidences under this evaluation's calibration, for cached pairs as for searched ones: the
  // cache keeps the evidence, so that another calibration needs no search.
  const ConfidenceCalibration* calibration =
      calibration_for(find.selection.metric, find.selection.calibration.get());
  for (PairResult& p : evaluation.pairs) {
    for (FoundBox& f : p.found) calibrate(f.confidence, f.box, calibration);
  }
  // A merge keeps what the cache had and names the rest.
  evaluation.pairs = kept_pairs(evaluation, dataset, jobs, searches.missing());
  evaluation.seconds = stopwatch.seconds();
  return evaluation;
}

}  // namespace lmk
