// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What a search returns (find_landmark.h): its matches, the candidates it turned down and why, and
// its statistics. Below the search methods (search_method.h), which fill it, and the confidence's
// competitor check (confidence/competitor.h), which reads it.

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/geometry/point_cloud.h"
#include "lmk/search/confidence/match_confidence.h"
#include "lmk/search/find_settings.h"
#include "lmk/search/metrics/error_metrics.h"

namespace lmk {

struct Match {
  /// The matched box in the scene frame: the capture box moved by T_scene_capture.
  Box box;
  /// The rigid motion taking the landmark from its capture frame into the scene.
  Eigen::Isometry3d T_scene_capture = Eigen::Isometry3d::Identity();
  double error = 0.0;
  ErrorTerms terms;
  std::size_t seed_index = 0;  ///< which seed this match came from
  Eigen::Vector3f seed_point;  ///< that seed's scene point
  int icp_iterations = 0;
  bool icp_converged = false;
  double votes = 0.0;  ///< fast: point-pair votes of the pose cluster this match came from
  /// How sure the match is, and what competes with it (match_confidence.h): set for every match
  /// the search returns, and for those turned down for it (SelectionSettings::min_confidence).
  MatchConfidence confidence;
  PointCloud aligned_points;  ///< only with execution.keep_aligned_points
};

/// Why a candidate was turned down (step 6), by the first test it failed, or removed by non-max
/// suppression.
enum class RejectionReason {
  error_above_threshold,
  colour_differs,  ///< over the threshold only by the colour term (issue #35): the shape fits
  coverage_too_low,
  empty_space_occupied,
  inside_a_better_match,  ///< its centre in a better match's box (fast.suppress_overlaps)
  too_little_shown,       ///< the view could not fix its pose (view_determinacy.h)
  confidence_too_low,
  suppressed_by_a_better_match,  ///< within nms_radius of a better candidate
};
inline constexpr std::size_t kRejectionReasons = 8;
/// The fast method's own statistics (zero for the reference method).
struct FastStats {
  std::size_t poses = 0;        ///< poses voted by the seeds
  std::size_t clusters = 0;     ///< pose clusters aligned coarsely
  std::size_t refined = 0;      ///< candidates refined fully
  double seconds_vote = 0.0;    ///< part of seconds_search: voting and clustering
  double seconds_coarse = 0.0;  ///< part of seconds_search: coarse alignment and pruning
  double seconds_fine = 0.0;    ///< part of seconds_search: refinement and scoring
};

/// Candidates left by non-max suppression and then rejected, counted by the first test they failed
/// (suppressed_by_a_better_match is not counted here: SearchStats::after_nms says how many
/// suppression left).
class RejectionCounts {
 public:
  std::size_t operator[](RejectionReason reason) const { return counts_[index(reason)]; }
  void add(RejectionReason reason) { ++counts_[index(reason)]; }

 private:
  static std::size_t index(RejectionReason reason) { return static_cast<std::size_t>(reason); }
  std::array<std::size_t, kRejectionReasons> counts_{};
};

struct SearchStats {
  double seconds_preprocess = 0.0;  ///< crop, downsample, indexing, seeding
  double seconds_search = 0.0;      ///< ICP and scoring of every seed
  double seconds_select = 0.0;      ///< non-max suppression and threshold
  double seconds_total = 0.0;
  std::size_t scene_points = 0;       ///< finite points in the input scene
  std::size_t scene_points_used = 0;  ///< after crop and downsampling
  std::size_t seeds = 0;
  std::size_t icp_iterations = 0;            ///< summed over seeds
  std::size_t after_nms = 0;                 ///< candidates left by non-max suppression
  FastStats fast;                            ///< the fast method's stages
  RejectionCounts rejected;                  ///< of those left by non-max suppression
  double threshold = 0.0;                    ///< the error threshold applied, in the metric's unit
  SearchMethod method = SearchMethod::fast;  ///< the search method run
  /// The metric applied, by its registry name: metrics are an open set (register_error_metric(),
  /// plugins), so a name, not an enum.
  std::string metric;
};

/// What JSON, logs and describe_rejections() say: "error above threshold", "colour differs",
/// "coverage too low", "empty space occupied", "inside a better match", "shows too little to fix
/// its pose", "confidence too low", "suppressed by a better match".
const char* to_string(RejectionReason reason);

/// A candidate that survived non-max suppression and was then turned down (step 6), with the
/// first test it failed: what a person looks at to see why an instance was not reported.
struct Rejection {
  Match candidate;
  RejectionReason reason = RejectionReason::error_above_threshold;
};

struct FindResult {
  std::vector<Match> matches;       ///< sorted by increasing error
  std::vector<Rejection> rejected;  ///< sorted by increasing error
  /// Only with execution.keep_suppressed: the candidates non-max suppression removed (within
  /// nms_radius of a better candidate), reason suppressed_by_a_better_match, in no set order.
  std::vector<Rejection> suppressed;
  SearchStats stats;
};

/// One line on what the search turned down and why, for users and logs: "" when nothing was, and
/// "no candidate pose ..." when the scene offered none.
std::string describe_rejections(const SearchStats& stats);

}  // namespace lmk
