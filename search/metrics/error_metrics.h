// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Candidate error metrics (CandidateError, Algorithm 2 of Huang & Cakmak, and variants), in a
// registry so that ablations select them by name.
//
// A candidate is the landmark moved by T_scene_capture (capture frame -> scene frame). Every metric
// works in the landmark's capture frame, mapping scene points by the inverse motion, so the
// landmark's k-d tree is built once per landmark rather than once per candidate as in the authors'
// code; distances are unchanged because the motion is rigid.

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/geometry/kdtree.h"
#include "lmk/geometry/point_cloud.h"
#include "lmk/occupancy/distance_field.h"

namespace lmk {

/// The support terms of the metrics that measure support (the visibility metrics and the sensor
/// metric): how much of the landmark the scene's surface supports, and what of it the scene's
/// sensor could not see.
struct SupportTerms {
  /// The fraction of landmark points with a scene surface within the support distance.
  double coverage = 0.0;
  /// Landmark points the scene's sensor could not see (behind a nearer surface, turned away,
  /// outside the view, no return), which count neither way.
  std::size_t unseen_points = 0;
  /// Sensor metric: landmark points the scene's sensor saw through, to a surface clearly behind.
  std::size_t seen_through_points = 0;
};

/// The landmark's observed-empty space in the scene, for the metrics that test it (the visibility
/// metrics and the sensor metric).
struct EmptySpaceTerms {
  std::size_t probes = 0;      ///< observed-empty voxels of the landmark tested
  std::size_t violations = 0;  ///< of those, voxels the scene occupies
  /// Mean distance of the violating voxels to the landmark surface, m (0 without violations).
  double violation_mean = 0.0;
  /// Sensor metric: the share of the landmark's observed-empty voxels the scene's sensor observed
  /// too, beyond the noise of the landmark's surface (NaN for the other metrics).
  double observed = std::numeric_limits<double>::quiet_NaN();
};

/// The colour term (search/metrics/colour_term.h; SelectionSettings::colour_weight), where it was
/// measured: where the landmark and the scene both have colour.
struct ColourTerms {
  /// The mean chroma distance between landmark points and the scene points supporting them, over
  /// `points` pairs.
  double difference = 0.0;
  std::size_t points = 0;
  double penalty = 0.0;  ///< what it added to the error, in the metric's unit
};

/// A metric's result with the terms it was made of, so a user can see why a candidate matched.
/// Every metric fills the distance sums; a term only some metrics measure is present only where
/// one did.
struct ErrorTerms {
  double scene_to_landmark_sum =
      0.0;  ///< sum of scene-point -> nearest-landmark-point distances, m
  std::size_t scene_to_landmark_count = 0;
  double landmark_to_scene_sum =
      0.0;  ///< sum of landmark-point -> nearest-scene-point distances, m
  std::size_t landmark_to_scene_count = 0;
  std::size_t scene_points_in_box = 0;         ///< scene points inside the candidate box
  std::optional<SupportTerms> support;         ///< the visibility metrics' and the sensor metric's
  std::optional<EmptySpaceTerms> empty_space;  ///< likewise
  std::optional<ColourTerms> colour;           ///< where colour was compared
  /// Visibility metrics: the factor (at most 1) the mean was scaled by because the candidate lies
  /// beyond SceneSettings::threshold_range (when set), where the depth noise raises a true match's
  /// error (match_error_scale()); 1 for the other metrics and nearer candidates.
  double range_scale = 1.0;
  /// range_scale x (sum of both terms) / (count of both terms) + the colour penalty, in the
  /// metric's own unit (m for the paper's distances). When no term was counted there is no evidence
  /// of a match, and the error is +infinity: defined, never NaN.
  double error = 0.0;

  void finish();  ///< computes `error` from the sums and counts

  /// The coverage where the metric measured it, NaN otherwise: what tables and the confidence's
  /// features read.
  double coverage() const {
    return support ? support->coverage : std::numeric_limits<double>::quiet_NaN();
  }
};

class SceneIndex;
struct Landmark;

/// The scene, indexed once per search.
struct SceneView {
  const SceneIndex& index;
  const PointCloud& points() const;  ///< at the paper's leaf (built on first use)
  const KdTree& tree() const;
};

/// The landmark in its capture frame, indexed once per landmark.
struct LandmarkView {
  const PointCloud& points;
  const KdTree& tree;
  const Box& box;            ///< the capture box, in the capture frame
  const Landmark& landmark;  ///< its grids
  /// Optional: each observed-empty voxel's distance to the nearest landmark point, m, in the order
  /// of landmark.empty_space.centres() (empty_space_distances()); metrics that need it beyond the
  /// distance field's band compute it when absent.
  const std::vector<float>* empty_distances = nullptr;
};

/// Each of `landmark`'s observed-empty voxel centres' distance to its nearest point (`tree` holds
/// its points), unbounded, in the order of landmark.empty_space.centres().
std::vector<float> empty_space_distances(const Landmark& landmark, const KdTree& tree);

using ErrorMetricFunction =
    std::function<ErrorTerms(const SceneView& scene, const LandmarkView& landmark,
                             const Eigen::Isometry3d& T_scene_capture)>;

/// How a metric's errors are shown: `value` in the metric's unit is `scale * value` in the shown
/// unit, printed with `decimals` decimals.
struct ErrorDisplay {
  double scale = 1000.0;
  int decimals = 1;
  std::string label = "mm";     ///< the shown unit, in sentences and axis labels
  std::string column = "mm";    ///< the shown unit as a short column suffix ("error_mm")
  std::string json_unit = "m";  ///< the metric's own unit, as JSON says it ("error_unit")
};

/// What a metric's coarse score sees once per fast search (step 3 of fast_search.h): the scene and
/// the landmark, and the points the coarse alignment works with.
struct CoarseView {
  const SceneIndex& index;
  const Landmark& landmark;
  const PointCloud& model;         ///< the landmark's points at the scene's coarse leaf
  const PointCloud& sparse_model;  ///< a few hundred of `model`: as many as fix a coarse pose
  /// As LandmarkView::empty_distances: set when the metric needs_empty_distances.
  const std::vector<float>* empty_distances;
  double coarse_leaf;  ///< the scene's coarse leaf, m
};

/// A cheap estimate of a metric's error for a coarsely aligned candidate, in the metric's unit.
/// Called from several threads at once. It may refer to its view's clouds: they must outlive it.
using CoarseScore = std::function<double(const Eigen::Isometry3f& T_scene_capture)>;
/// Builds a metric's coarse score for one search.
using CoarseScoreFactory = std::function<CoarseScore(const CoarseView& view)>;

/// An error metric, with everything the searches and the reports ask of it: nothing outside the
/// registry looks at which metric it is.
struct ErrorMetric {
  std::string name;
  std::string description;
  ErrorMetricFunction evaluate;
  /// The error threshold used when a search sets none, in the metric's unit.
  double default_threshold = 0.0;
  ErrorDisplay display;
  /// The fast search's coarse score, which ranks the coarsely aligned candidates and prunes those
  /// beyond prune_bound(). Empty: the metric has none, and the best-voted candidates go on to the
  /// fine alignment unpruned, up to FastSettings::max_refined.
  CoarseScoreFactory coarse_score;
  /// The coarse score beyond this many default thresholds drops a candidate: a coarse pose is a
  /// leaf or so from its fine one, so a true match's coarse score lies above its final error.
  double prune_ratio = 2.5;
  /// Its residuals are divided by the depth noise expected at each point already (its unit is
  /// that noise's sigma): a match's confidence then takes its error's spread as 1, not as the
  /// noise in metres.
  bool noise_normalised = false;
  /// It reads LandmarkView::empty_distances (and CoarseView's): the search computes them for it.
  bool needs_empty_distances = false;
  /// Landmark points hidden behind nearer scene surfaces count neither way (hidden_behind(), in
  /// search/metrics/grid_metrics.h); its coarse score hides them too.
  bool hides_occluded = false;

  /// The coarse score beyond which the fast search drops a candidate, in the metric's unit.
  double prune_bound() const { return prune_ratio * default_threshold; }
};

/// `value` (an error or a threshold of `metric`) with its unit: "5.5 mm", "1.30 sigma".
std::string format_error(double value, const ErrorMetric& metric);
/// The same for the metric called `name`.
std::string format_error(double value, const std::string& name);

/// Every registered metric: the built-in ones in a fixed order ("paper", "rapid", "vdb",
/// "visibility", "projective", "sensor"), then those registered, in their order. The first call
/// loads the metric plugins that $LMK_METRIC_PLUGINS names (load_metric_plugins()).
const std::vector<ErrorMetric>& error_metrics();
/// What register_error_metric() takes of a metric: a name this long at most, bytes; a default
/// threshold this large at most (in the metric's unit: a million metres, or sigmas, is no error a
/// search can use); a prune ratio this large at most.
inline constexpr std::size_t kMaxMetricName = 64;
inline constexpr double kMaxMetricThreshold = 1e6;
inline constexpr double kMaxPruneRatio = 1e3;

/// Adds `metric` to the registry, so that every search, evaluation, ablation, the CLI, Python and
/// the server know it by its name. Register before searching: the registry is not guarded against
/// searches running at the same time. lmk::Error when the name is empty, taken or not printable
/// text, the description or the display's words are not printable, the evaluation is missing,
/// the default threshold is not in (0, kMaxMetricThreshold], the prune ratio not in
/// [1, kMaxPruneRatio], or the display's scale is not positive and finite.
void register_error_metric(ErrorMetric metric);
/// The environment variable naming metric plugins: shared libraries, separated by ':', each
/// exporting `extern "C" void lmk_register_error_metrics()`, which calls register_error_metric().
/// A researcher's metric then runs in lmk's own tools without rebuilding them.
constexpr const char* kMetricPluginsVariable = "LMK_METRIC_PLUGINS";
/// The registered metrics' names, in the registry's order.
std::vector<std::string> error_metric_names();
/// The metric called `name`; throws lmk::Error listing the known names otherwise.
const ErrorMetric& find_error_metric(const std::string& name);

/// The finite scene indices inside `box` (scene frame), found through the scene tree.
Indices scene_points_in_box(const SceneView& scene, const Box& box);

}  // namespace lmk
