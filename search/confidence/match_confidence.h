// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// How sure a match is (issue #45; docs/evaluation.md, "Confidence"). A search reports evidence,
// not verdicts: each match carries how clearly it beats the best *different* pose the search met
// (a slide along the same structure, a turn, a look-alike elsewhere), in units of its error's own
// uncertainty at its range; how freely the scene lets it move within the noise; and how much of
// the landmark the scene shows. A calibration fitted on labelled data (confidence_calibration.h)
// turns that into the probability that the match lies within the evaluation's tolerance of a true
// instance. Deciding what to do with it (act, look again, refuse) is the caller's: pbd's
// min_confidence, `lmk find --min-confidence`.

#include <Eigen/Geometry>
#include <limits>
#include <string>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/landmark/capture_findings.h"
#include "lmk/landmark/slide_check.h"

namespace lmk {

/// Two poses closer than this are one pose: the evaluation's tolerance (docs/datasets.md, one inch
/// between box centres and 15 degrees), against which the probability is calibrated.
inline constexpr double kSamePoseDistance = 0.0254;  ///< m
inline constexpr double kSamePoseAngle = 0.2618;     ///< rad

/// The confidence a robot's program needs by default to act on a match (PlanSettings::
/// min_confidence): chosen from the measurements of docs/evaluation.md, "Confidence".
inline constexpr double kDefaultMinConfidence = 0.8;

/// The best-scoring candidate of the search that is a different pose from a match.
struct Competitor {
  /// What separates it from the match: a slide (its centre beyond kSamePoseDistance, its box
  /// overlapping the match's), a turn (its centre within kSamePoseDistance, turned beyond
  /// kSamePoseAngle), or a look-alike elsewhere (its centre outside the match's box).
  enum class Kind { none, slide, turn, look_alike };
  Kind kind = Kind::none;
  Eigen::Isometry3d T_scene_capture = Eigen::Isometry3d::Identity();
  Box box;                                                 ///< scene frame
  double error = std::numeric_limits<double>::infinity();  ///< in the metric's unit
  double distance = 0.0;                                   ///< between the box centres, m
  double angle = 0.0;  ///< of the rotation between the two poses, rad
};

/// "none", "slide", "turn", "look-alike".
const std::vector<std::string>& setting_names(Competitor::Kind);

/// The evidence of one match and the probability made of it.
struct MatchConfidence {
  /// The calibrated probability that the match lies within kSamePoseDistance and kSamePoseAngle
  /// of a true instance, in [0, 1]. NaN when no calibration applies (a metric it was not fitted
  /// for: see ConfidenceCalibration::metric).
  double probability = std::numeric_limits<double>::quiet_NaN();
  /// (competitor error - match error) / error_sigma: how many of its own uncertainties the match
  /// beats its competitor by; +infinity when the search met no different pose.
  double margin = std::numeric_limits<double>::infinity();
  /// The same against the best different pose whose box overlaps the match's (a slide or a turn),
  /// and against the best look-alike elsewhere: the two kinds of doubt, which the calibration
  /// weighs apart (several true instances are look-alikes of each other).
  double local_margin = std::numeric_limits<double>::infinity();
  double elsewhere_margin = std::numeric_limits<double>::infinity();
  /// The uncertainty of the match's error from the depth noise alone, in the metric's unit: the
  /// residual sigma at the match's range (model_noise) over the square root of the supporting
  /// landmark points (for the sensor metric, whose residuals are in sigma, 1 over it).
  double error_sigma = std::numeric_limits<double>::quiet_NaN();
  /// The match's error over the residual sigma at its range: how well it fits for its range.
  double fit = std::numeric_limits<double>::quiet_NaN();
  double range = std::numeric_limits<double>::quiet_NaN();  ///< scene sensor to box centre, m
  /// The residual sigma between a landmark point and the scene's surface at the match, m, from the
  /// sensor model (DepthNoise::residual_sigma at the capture's and the match's range): what the
  /// margins, fit and freedom are in units of.
  double model_noise = std::numeric_limits<double>::quiet_NaN();
  /// The same from the noise measured in the frames (issue #59): scene_noise, capture_noise and
  /// the floor. A margin or fit in these units is the one above times model_noise / measured_noise
  /// (the calibration's *_measured features).
  double measured_noise = std::numeric_limits<double>::quiet_NaN();
  /// One depth measurement's noise at the match, measured in the scene's own frame around it
  /// (geometry/frame_noise.h: the spread of the frame's planar surfaces at the match's range), m.
  /// Where the frame does not measure it (an unorganised cloud, too few planes at that range) the
  /// sensor model's (SceneSettings::depth_noise) stands in, and scene_noise_measured is false.
  double scene_noise = std::numeric_limits<double>::quiet_NaN();
  bool scene_noise_measured = false;
  /// The same in the capture frame at the landmark (CaptureFindings::noise, or the model's), m.
  double capture_noise = std::numeric_limits<double>::quiet_NaN();
  /// The landmark as the evidence sees it, inputs of their own rather than hidden in the margin:
  /// its box's diagonal (m), its points, and the share of them the scene's sensor can see at the
  /// match (in the image, with a measured depth not clearly in front of them).
  double landmark_size = std::numeric_limits<double>::quiet_NaN();
  std::size_t landmark_points = 0;
  double seen_fraction = std::numeric_limits<double>::quiet_NaN();
  /// How the match is seen against how the landmark was captured: the capture's range (its sensor
  /// to its box centre, m), and the angle between the two lines of sight in the landmark's frame
  /// (rad; with several views, to the nearest view). A landmark seen from twice as far, or from
  /// another side, shows the search less of what it knows.
  double capture_range = std::numeric_limits<double>::quiet_NaN();
  double view_change = std::numeric_limits<double>::quiet_NaN();
  /// What the capture check found about the landmark (Landmark::findings): a prior every match of
  /// it carries.
  CaptureFindings capture;
  /// Landmark points (at the scene's coarse leaf, the noise's independence scale) that have a scene
  /// surface within the support distance at the match.
  std::size_t support = 0;
  /// The freest motion of the supporting points against the scene's normals at the match (the
  /// slide check's H, slide_check.h, scene frame), and how far it moves them within the noise, m.
  Slide freest;
  double freedom = std::numeric_limits<double>::quiet_NaN();
  double coverage = std::numeric_limits<double>::quiet_NaN();  ///< the metric's, when it has one
  /// How much of the empty-space allowance the match uses: the landmark's observed-empty voxels
  /// the scene occupies over the most selection lets through (SelectionSettings::
  /// max_empty_space_violation), in [0, 1]; 0 for metrics that do not test empty space. Something
  /// standing in a free patch, or a slid pose's own surface in the margin, raises it.
  double intrusion = 0.0;
  /// A flat landmark (flat_normal()) only: the share of its free space (the observed-empty voxels
  /// beyond the noise of its surface) the scene's sensor sees empty at the match. A flat surface
  /// hides none of its own free space, so what is not seen empty is hidden by something else or
  /// returned nothing: an object standing in the patch whose sides the sensor sees only edge-on, or
  /// the shadow of one beside it. NaN for other landmarks and scenes without a range image.
  double free_space_seen = std::numeric_limits<double>::quiet_NaN();
  /// free_space_seen leaves more of the free space unseen than the empty-space allowance
  /// (SelectionSettings::max_empty_space_violation): nothing confirms the patch is free, and the
  /// probability is 0 whatever the calibration says.
  bool free_space_unconfirmed = false;
  Competitor competitor;  ///< the closest-scoring different pose, local or elsewhere
  /// One line on why the probability is below a half ("a pose 8 cm along the box's x fits within
  /// the noise", "only 31% of the landmark is seen"); empty otherwise.
  std::string doubt;
};

/// Whether a match of calibrated confidence `probability` passes the cut `min_confidence`: every
/// match at a cut of 0, none without a probability (NaN) above it. The one rule of
/// SelectionSettings::min_confidence, the evaluation's cut and PlanSettings::min_confidence.
inline bool passes_confidence(double probability, double min_confidence) {
  return min_confidence <= 0.0 || probability >= min_confidence;
}

/// The doubt line for `confidence`, the match's box `box` (scene frame) naming the directions.
std::string describe_doubt(const MatchConfidence& confidence, const Box& box);

}  // namespace lmk
