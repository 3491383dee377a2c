// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Batch evaluation of a search method over a dataset (docs/evaluation.md): every
// (scene, landmark) pair searched, each result matched to the ground truth, and the paper's
// precision/recall table under its three assumptions, per setting.
//
// Each pair's result is cached on disk as soon as it is known, keyed by the search settings, the
// dataset's content and the lmk version, so that an interrupted evaluation resumes where it
// stopped and an ablation reuses every variant it has already run.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lmk/datasets/dataset.h"
#include "lmk/datasets/shard.h"
#include "lmk/eval/evaluation_protocol.h"
#include "lmk/search/find_landmark.h"

namespace lmk {

struct EvaluationSettings {
  /// The search: method, metric, threshold, max_seeds, ... (threads and progress are ignored: the
  /// evaluation runs one search per thread).
  FindSettings find;
  bool in_context_only = false;  ///< search in-context pairs only (assumptions 2 and 3)
  int threads = 0;               ///< pairs searched at once; 0 uses every core
  std::string cache_dir;         ///< where pair results are cached; empty: no cache
  std::optional<Shard> shard;    ///< only this shard's pairs; unset: every pair
  /// Merge: take every pair from the cache and search none; those not there are listed in
  /// Evaluation::missing. Needs a cache.
  bool cached_only = false;
  MatchTolerance tolerance;
  /// Where the dataset gives a landmark no symmetry and its capture found an axis of revolution
  /// (capture_symmetry(), landmark/shape_check.h), count a pose that differs from the truth only by
  /// a turn about that axis as right (issue #59). lmk eval --no-capture-symmetry turns it off, to
  /// see the rule's effect on its own.
  bool capture_symmetry = true;
  /// Called after each pair with (pairs done, pairs in all, of those done how many from the cache),
  /// possibly from several threads at once.
  std::function<void(std::size_t, std::size_t, std::size_t)> progress;
  /// Polled before each search; once it returns true no further search starts, the searches under
  /// way finish and are cached, and evaluate() throws lmk::Interrupted saying how many pairs are
  /// kept. The next run with the same cache resumes from them.
  std::function<bool()> stop_requested;
};

/// A match as the evaluation keeps it.
struct FoundBox {
  Box box;  ///< scene frame
  double error = 0.0;
  ErrorTerms terms;
  /// Its evidence and calibrated probability (match_confidence.h), the probability under the
  /// evaluation's calibration (EvaluationSettings::find.selection.calibration) whether the pair was
  /// searched or read from the cache.
  MatchConfidence confidence;
};

struct PairResult {
  std::string scene, landmark, setting;
  bool in_context = false;
  /// The dataset's symmetry of the landmark, or the one its capture found
  /// (EvaluationSettings::capture_symmetry; then symmetry_from_capture).
  Symmetry symmetry;
  bool symmetry_from_capture = false;
  std::vector<Eigen::Isometry3d> truth;
  std::vector<double> truth_hidden;  ///< the dataset's hidden fraction per instance, if it has them
  /// Every match the search kept with an error below twice the threshold, or twice the metric's
  /// default threshold if that is larger (see matches_within), best first. The threshold is applied
  /// afterwards, as the search's own selection does it (non-max suppression first, then the
  /// threshold), so that one search also serves the precision/recall curve against the threshold.
  std::vector<FoundBox> found;
  /// The search's wall time on one thread, with its share of the scene's preprocessing (the scene
  /// is indexed once for all of its pairs).
  double seconds = 0.0;
  std::size_t seeds = 0;   ///< seeds the search started from
  std::string rejections;  ///< describe_rejections() of the search
  /// The scene's sensor position, scene frame: the range of each instance and match.
  Eigen::Vector3d sensor_position = Eigen::Vector3d::Zero();
  /// Where the landmark was demonstrated from (issue #35; not cached: read from the landmark on
  /// every run): its views' sensor origins (one for a landmark of one view), its up axis and its
  /// box pose, all in the capture frame.
  std::vector<Eigen::Vector3d> view_origins;
  Eigen::Vector3d landmark_up = -Eigen::Vector3d::UnitY();
  Eigen::Isometry3d capture_box = Eigen::Isometry3d::Identity();
  double landmark_size = 0.0;  ///< the capture box's diagonal, m (issue #59: the table by size)
  bool from_cache = false;     ///< read from the cache rather than searched in this run
};

/// An instance of which the sensor sees less than a fifth of the landmark (its recorded hidden
/// fraction is at least this) is ignored by the protocol: effectively unseen, as an object out of
/// the view, so neither a miss nor, when found, a false positive.
inline constexpr double kIgnoredHiddenFraction = 0.8;

/// The search each pair runs, from the evaluation's resolved settings: one thread, no callback,
/// matches kept up to twice the larger of the threshold and the metric's default (see
/// PairResult::found), and the scene's own up axis where the dataset gives one.
FindSettings pair_search(const FindSettings& find, const DatasetScene& scene);

/// The matches of `pair` with an error below `threshold` and a confidence of at least
/// `min_confidence` (passes_confidence(), match_confidence.h), as PairInput for the protocol, with
/// instances hidden at least kIgnoredHiddenFraction ignored.
PairInput matches_within(const PairResult& pair, double threshold, double min_confidence = 0.0);

struct Evaluation {
  std::string dataset;            ///< the dataset's name
  std::string fingerprint;        ///< dataset_fingerprint() of it
  EvaluationSettings settings;    ///< as run: settings.find resolved (FindSettings::resolved())
  std::vector<PairResult> pairs;  ///< in dataset order: scene by scene, landmark by landmark
  /// With settings.cached_only: the pairs (scene, landmark) the cache lacks, in dataset order.
  std::vector<std::pair<std::string, std::string>> missing;
  double seconds = 0.0;  ///< wall time of the whole run
};

/// Searches every pair of the dataset in `dir` (or its in-context pairs only), resuming from the
/// cache. Deterministic: the pairs' results do not depend on the thread count or on the cache.
Evaluation evaluate(const std::string& dir, const Dataset& dataset,
                    const EvaluationSettings& settings);

/// The cache key of a search configuration on a dataset: a hash of the settings that change
/// results, the dataset fingerprint and the lmk version.
std::string evaluation_cache_key(const FindSettings& find, const std::string& fingerprint);

/// The default cache directory: $LMK_CACHE_DIR, else $XDG_CACHE_HOME/lmk, else ~/.cache/lmk,
/// else .lmk-cache in the working directory.
std::string default_cache_dir();

}  // namespace lmk
