// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The settings of FindLandmark, one struct per stage of the search, each field described once
// (geometry/settings_schema.h) with its unit, its limits and its reason:
//
//   scene      SceneSettings      steps 1-2: crop, downsample, the scene's grids and up axis
//   sampling   SamplingSettings   step 3: the random seeds (both methods)
//   reference  ReferenceSettings  step 4 of the paper's method
//   fast       FastSettings       the fast method's voting and coarse-to-fine alignment
//   selection  SelectionSettings  steps 5-6: metric, non-max suppression, threshold, coverage
//   execution  ExecutionSettings  threads, progress, extra output: how to run, not what is found
//
// Validation, JSON, the evaluation cache key, `lmk ablate --vary KEY=...` and the CLI flags all
// derive from the descriptions, so every field reaches each of them. Keys are the fields' names in
// kebab-case (`--max-tilt`, `--vary max-tilt=30,45`) and are unique across the stages.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/settings_schema.h"
#include "lmk/geometry/worker_threads.h"
#include "lmk/landmark/scene_settings.h"
#include "lmk/search/metrics/error_metrics.h"

namespace lmk {

struct ConfidenceCalibration;  // confidence_calibration.h

/// The search methods find_landmark accepts: the fast search (detail/fast_search.h) and the
/// paper's Algorithm 1 as published (detail/reference_search.h).
enum class SearchMethod { fast, reference };
/// "fast", "reference": the method's name in flags, JSON and results.
const std::vector<std::string>& setting_names(SearchMethod);

/// The names of the search methods, in order.
inline const std::vector<std::string>& search_methods() { return setting_names(SearchMethod{}); }

/// Which orientations the fast search tries: "upright", any rotation about the up axis and a tilt
/// of the landmark's capture up axis up to a limit; "full", all of SO(3).
enum class Orientations { upright, full };
const std::vector<std::string>& setting_names(Orientations);

/// Step 3: which scene points seed the search.
struct SamplingSettings {
  std::uint64_t seed = 0;  ///< random seed of the sampling
  /// At most this many seeds. Unset: the method's own (FindSettings::resolved()): the paper's 1000
  /// for the reference; 2000 for fast, whose seeds cost little and whose seed count otherwise
  /// follows seeds_per_instance (a small landmark in a large scene wants more than 1000).
  std::optional<std::size_t> max_seeds;

  template <class Self, class Visit>
  static void describe(Self& s, Visit&& visit) {
    // Any seed costs the same: the bound only keeps every value a plain whole number.
    visit(SettingInfo("seed", "Random seed of the seed sampling (0 to 10^18)").within(0, 1e18),
          s.seed);
    visit(SettingInfo("max_seeds",
                      "Most seeds (default: 1000 for the reference, as the paper; 2000 for fast)")
              .within(1, 1e6),  // a 640 x 480 frame has 307,200 points
          s.max_seeds);
  }
};

/// The paper's Algorithm 1, steps 3-4, as the authors ran it.
struct ReferenceSettings {
  double sample_fraction = 0.05;  ///< step 3: fraction of the downsampled points used as seeds
  int icp_iterations = 50;        ///< step 4: ICP iterations per seed (PCL's ICP)

  template <class Self, class Visit>
  static void describe(Self& s, Visit&& visit) {
    visit(SettingInfo("sample_fraction", "Reference: fraction of the scene points used as seeds")
              .within(0.0, 1.0)
              .above(0.0),
          s.sample_fraction);
    // PCL's ICP converges within tens of iterations; 1000 per seed is already hours a search.
    visit(SettingInfo("icp_iterations", "Reference: ICP iterations per seed").within(1, 1000),
          s.icp_iterations);
  }
};

/// The fast method: point pair voting over orientations, then coarse-to-fine alignment.
struct FastSettings {
  /// As many seeds as put about this many on one instance of the landmark (the scene's coarse
  /// points over the landmark's, times this). Each seed on an instance votes for its pose, so a
  /// handful leave room for a half-occluded instance and for seeds on its edges, whose normals are
  /// poor, while a search costs a few hundred seeds rather than a thousand (docs/evaluation.md).
  double seeds_per_instance = 8.0;
  Orientations orientations = Orientations::upright;  ///< tilts up to max_tilt when upright
  double max_tilt = 1.0471975511965976;               ///< rad (60 degrees)
  /// Point pair voting samples the landmark and the scene at this fraction of the landmark's
  /// diameter (at least the coarse leaf); the value is docs/evaluation.md's "Tuning history".
  double vote_leaf_fraction = 0.07;
  int poses_per_seed = 3;  ///< best-voted poses kept per seed
  /// Pose clusters aligned coarsely: enough for every instance's poses once seeds keep off noisy
  /// planes, few enough not to spend the search aligning look-alikes (docs/evaluation.md, "Tuning
  /// history").
  std::size_t max_candidates = 250;
  /// A coarse fit beyond this times the metric's own prune bound (ErrorMetric::prune_bound())
  /// drops a candidate: 1 prunes where the metric says.
  double prune_scale = 1.0;
  std::size_t max_refined = 16;  ///< candidates refined fully
  bool refine = true;            ///< Ceres robust refinement of the finalists
  /// Drop a match whose box centre lies in a better match's box (exclusive_boxes): the same object
  /// found twice. Not in the paper, whose non-max suppression looks at box centres only, so the
  /// reference method, which keeps to the paper, does not apply it.
  bool suppress_overlaps = true;

  template <class Self, class Visit>
  static void describe(Self& s, Visit&& visit) {
    // The seed count follows this, up to max_seeds; beyond 1000 a seed lands on every coarse point.
    visit(SettingInfo("seeds_per_instance", "Fast: seeds expected on one instance of the landmark")
              .within(1, 1000),
          s.seeds_per_instance);
    visit(SettingInfo("orientations",
                      "Fast: 'upright' (any yaw, tilt up to --max-tilt) or 'full' (all of SO(3))")
              .names_of<Orientations>(),
          s.orientations);
    visit(SettingInfo("max_tilt", "Fast, upright: largest tilt of the landmark's up axis")
              .within(0.0, 3.14159265358979323846)
              .in_degrees(),
          s.max_tilt);
    visit(SettingInfo("vote_leaf_fraction",
                      "Fast: voting sample spacing, as a fraction of the landmark's diameter")
              .within(0.0, 1.0)
              .above(0.0),
          s.vote_leaf_fraction);
    // Counts of poses, each aligned in turn: bounds far above any useful value (3, 250, 16 by
    // default) that keep a request from asking for hours of work or an allocation beyond memory.
    visit(SettingInfo("poses_per_seed", "Fast: best-voted poses kept per seed").within(1, 100),
          s.poses_per_seed);
    visit(SettingInfo("max_candidates", "Fast: pose clusters aligned coarsely").within(1, 1e5),
          s.max_candidates);
    // A hundred times the metric's bound prunes nothing a fine alignment could save.
    visit(SettingInfo("prune_scale",
                      "Fast: scale of the metric's own coarse-fit bound beyond which a candidate "
                      "is dropped")
              .positive()
              .at_most(100.0),
          s.prune_scale);
    visit(SettingInfo("max_refined", "Fast: candidates refined fully").within(1, 1e4),
          s.max_refined);
    visit(SettingInfo("refine", "Fast: Ceres robust refinement of the finalists"), s.refine);
    visit(SettingInfo("suppress_overlaps",
                      "Fast: drop a match whose centre lies in a better match's box"),
          s.suppress_overlaps);
  }
};

/// Steps 5-6: how candidates are scored, suppressed and accepted.
struct SelectionSettings {
  /// Error metric, by registry name (error_metrics.h). Empty: the method's own, "visibility" for
  /// fast and "paper" for reference.
  std::string metric;
  double nms_radius = 0.03;  ///< step 5: non-max suppression radius on box centres, m
  /// Step 6: matches need an error below this, in the metric's unit (m, or sigma for `sensor`:
  /// ErrorMetric::display). Unset: the metric's default threshold.
  std::optional<double> threshold;
  /// Matches need at least this fraction of their points supported by the scene (only for metrics
  /// that measure coverage).
  double min_coverage = 0.5;
  /// Matches may have at most this fraction of the landmark's observed-empty voxels occupied by
  /// the scene (only for metrics that test empty space). The landmark's empty space keeps a margin
  /// from its surface that absorbs depth noise and the pose error of a true match, so a true
  /// instance leaves it empty; the 1% allowance is for the Kinect's isolated flying pixels at
  /// depth edges, not for surfaces.
  double max_empty_space_violation = 0.01;
  /// The colour term (issue #35; search/metrics/colour_term.h), only where the landmark and the
  /// scene both have colour: the share of the threshold added to the error per unit of mean chroma
  /// difference beyond colour_tolerance. 0 compares shapes only, as the paper.
  double colour_weight = 10.0;
  /// The mean chroma difference a true match may show at no cost: the camera's white balance and
  /// the light changing between the demonstration and the scene.
  double colour_tolerance = 0.1;
  /// Matches need at least this calibrated confidence (match_confidence.h): the probability that
  /// the match lies within the evaluation's tolerance of a true instance. 0 keeps every match,
  /// as before confidences existed; a robot's programs set their own cut (pbd's min_confidence).
  double min_confidence = 0.0;
  /// The calibration that turns a match's evidence into its confidence; null: lmk's built-in one
  /// (builtin_confidence_calibration()). A C++ value, like progress: no description, JSON or flag
  /// of its own (`--confidence-calibration FILE` reads one in the CLI), so that no request names
  /// a file for a server to read.
  std::shared_ptr<const ConfidenceCalibration> calibration;

  template <class Self, class Visit>
  static void describe(Self& s, Visit&& visit) {
    visit(SettingInfo("metric", "Error metric (default: visibility for fast, paper for reference)")
              .one_of(error_metric_names())
              .or_default(),
          s.metric);
    // A radius in the scene: at most as far as any depth camera sees. The threshold is in the
    // metric's unit (m, or sigma for `sensor`): 100 is far beyond any useful value of either.
    visit(SettingInfo("nms_radius", "Non-max suppression radius on box centres, m")
              .positive()
              .at_most(kMaxSensorRange),
          s.nms_radius);
    visit(SettingInfo("threshold",
                      "Largest error of a match, in the metric's unit (default: the metric's own)")
              .positive()
              .at_most(100.0),
          s.threshold);
    visit(SettingInfo("min_coverage", "Least fraction of landmark points with scene support")
              .within(0.0, 1.0),
          s.min_coverage);
    visit(SettingInfo("max_empty_space_violation",
                      "Largest fraction of the landmark's empty space the scene may occupy")
              .within(0.0, 1.0)
              .also("max-empty-violation"),
          s.max_empty_space_violation);
    // A weight of 50 charges a whole threshold for a chroma difference of 0.02, the noise between
    // two views of one surface: beyond any use.
    visit(SettingInfo("colour_weight",
                      "Colour: share of the threshold added per unit of chroma difference "
                      "(0: shape only)")
              .within(0.0, 50.0)
              .also("color-weight"),
          s.colour_weight);
    visit(SettingInfo("colour_tolerance",
                      "Colour: mean chroma difference of a true match, at no cost")
              .within(0.0, 1.5)
              .also("color-tolerance"),
          s.colour_tolerance);
    visit(SettingInfo("min_confidence",
                      "Least calibrated confidence of a match, 0 to 1 (0: every match)")
              .within(0.0, 1.0),
          s.min_confidence);
  }
};

/// How to run a search. None of it changes what is found.
struct ExecutionSettings {
  int threads = 0;  ///< worker threads; 0 uses every core
  /// Return each match's landmark points in the scene frame. A request of C++ callers for more
  /// output, not a setting: like progress, it has no description, JSON or flag.
  bool keep_aligned_points = false;
  /// Return the candidates non-max suppression removed (FindResult::suppressed): what a diagnosis
  /// of a miss looks at (lmk eval --explain). Like keep_aligned_points, a request for more output.
  bool keep_suppressed = false;
  /// Called after each seed with (seeds done, seeds in all), possibly from several threads at once.
  std::function<void(std::size_t, std::size_t)> progress;
  /// Called between pieces of the work, the scene's indexing included, at least every 200 ms or
  /// so (geometry/stop_check.h); what it throws ends the search. Like progress, no description.
  StopCheck stop;

  template <class Self, class Visit>
  static void describe(Self& s, Visit&& visit) {
    visit(SettingInfo("threads", "Worker threads; 0 uses every core")
              .within(0, max_worker_threads())  // geometry/worker_threads.h
              .not_affecting_results(),
          s.threads);
  }
};

struct FindSettings {
  SearchMethod method = SearchMethod::fast;
  SceneSettings scene;
  SamplingSettings sampling;
  ReferenceSettings reference;
  FastSettings fast;
  SelectionSettings selection;
  ExecutionSettings execution;

  template <class Self, class Visit>
  static void describe(Self& s, Visit&& visit) {
    visit(SettingInfo("method", "Search method").names_of<SearchMethod>(), s.method);
  }

  /// These settings as the search applies them: every default that depends on the method or on
  /// another setting spelt out (selection.metric, selection.threshold, sampling.max_seeds,
  /// scene.field_band). A search resolves its settings once, at entry; what follows, and what
  /// reports a search (stats, tables, the evaluation's cache key), reads the fields.
  FindSettings resolved() const;
};

/// Calls f(name, group) for each stage's settings, in the order of the search.
template <class Find, class F>
void for_each_settings_group(Find& s, F&& f) {
  f("scene", s.scene);
  f("sampling", s.sampling);
  f("reference", s.reference);
  f("fast", s.fast);
  f("selection", s.selection);
  f("execution", s.execution);
}

/// Whether the stage named `group` can change what `method` finds: scene, sampling and selection
/// always; a method's own group (named as the method: fast, reference) only for that method;
/// execution never.
bool settings_group_affects(SearchMethod method, const std::string& group);

/// Throws lmk::Error naming the stage, the field and its flag for the first setting out of its
/// limits, in the flag's unit ("find: fast.max_tilt (--max-tilt): 229.18 must be finite and in
/// [0, 180] degrees").
void validate(const FindSettings& settings);

/// Sets the setting whose key is `key` ("max-tilt"; the field name "max_tilt" and "method" work
/// too) from text as written on the command line: numbers in the flag's unit (degrees for angles),
/// true/false, "X Y Z" for a vector, "CX CY CZ SX SY SZ [ROLL PITCH YAW]" for a box. Throws
/// lmk::Error naming the known keys for an unknown one, and for a bad value.
void set_find_setting(FindSettings& settings, const std::string& key, const std::string& text);

/// Every key set_find_setting accepts, in stage order; with `results_only`, only those of settings
/// that can change what is found (not threads).
std::vector<std::string> find_setting_keys(bool results_only = false);

}  // namespace lmk
