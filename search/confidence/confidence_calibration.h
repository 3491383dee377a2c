// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The calibration that turns a match's evidence (match_confidence.h) into a probability: a
// logistic model over a few named features, fitted on labelled searches by
// `lmk calibrate-confidence` (eval/confidence_fit.h) and stored as a versioned JSON file
// (docs/file-formats.md). lmk ships one, fitted for the default metric
// (search/confidence/data/confidence_calibration.json, compiled in);
// `--confidence-calibration FILE` reads another.
//
//   {"format": "lmk-confidence-calibration", "version": 1, "metric": "visibility",
//    "fitted_on": "...", "bias": b, "weights": {"local_margin": w1, ...}}
//
// p = 1 / (1 + exp(-(b + sum_k w_k f_k))), each f_k a feature of confidence_features().

#include <map>
#include <string>
#include <vector>

#include "lmk/search/confidence/match_confidence.h"

namespace lmk {

inline constexpr int kConfidenceCalibrationVersion = 1;

struct ConfidenceCalibration {
  std::string metric;     ///< the error metric it was fitted for; others get no probability
  std::string fitted_on;  ///< what it was fitted on, for people
  double bias = 0.0;
  std::map<std::string, double> weights;  ///< by feature name (confidence_feature_names())
};

/// The features a calibration may weigh, each a bounded function of the evidence:
///   local_margin       margin against the best slide or turn, in error sigmas, capped at +-20,
///                      as sign(m) log(1 + |m|) (no rival: the cap)
///   elsewhere_margin   the same against the best look-alike elsewhere
///   fit                the error over the residual sigma at the match's range, capped at 10
///   coverage           share of the landmark the scene supports (1 for metrics without it)
///   log_freedom        log10 of the freedom over kSamePoseDistance, within [-3, 3]
///   range              m, capped at 5
///   intrusion          the share of the empty-space allowance the match uses, in [0, 1]
///   log_size           log10 of the landmark box's diagonal over 10 cm, within [-1, 1]
///   log_support        log10 of the supporting landmark points (at least 1)
///   seen_fraction      share of the landmark the scene's sensor can see at the match (1 unknown)
///   capture_slide      log10 of the capture check's slide over kSamePoseDistance, within [-3, 3]
///                      (-3: none; 0 for a landmark without findings)
///   capture_look_alike 1 over the capture check's look-alike error ratio; 1 when it did not find
///                      the landmark itself, 0 without a look-alike or without the check
///   capture_warned     1 when the capture check warned (CaptureFindings::warned), else 0
///   range_change       |log2| of the match's range over the capture's, within [0, 2]
///   view_change        the angle between the capture's and the scene's lines of sight, rad
///   local_margin_measured, elsewhere_margin_measured, fit_measured
///                      the three above in units of the noise measured in the frames
///                      (MatchConfidence::measured_noise) instead of the sensor model's
/// The features after `intrusion` came with issue #59; a file that weighs none of them reads and
/// applies as before.
const std::vector<std::string>& confidence_feature_names();

/// The features of `confidence`, in the order of confidence_feature_names().
std::vector<double> confidence_features(const MatchConfidence& confidence);

/// The calibrated probability of `confidence` under `calibration`.
double calibrated_probability(const MatchConfidence& confidence,
                              const ConfidenceCalibration& calibration);

/// The calibration that applies to a search with `metric`: `chosen` (the built-in one when null)
/// if it was fitted for that metric, else null (no probability).
const ConfidenceCalibration* calibration_for(const std::string& metric,
                                             const ConfidenceCalibration* chosen);

/// Sets `confidence.probability` under `calibration` (NaN when null; 0 for free space nothing
/// confirms, MatchConfidence::free_space_unconfirmed) and, below a half, its doubt line for a match
/// with box `box` (scene frame); clears the doubt otherwise.
void calibrate(MatchConfidence& confidence, const Box& box,
               const ConfidenceCalibration* calibration);

/// Reads a calibration from JSON text; `where` (a file name) starts every message. Throws
/// lmk::Error for anything but the format above: another format or a newer version, an unknown
/// feature, a weight or bias that is not a finite number.
ConfidenceCalibration parse_confidence_calibration(const std::string& text,
                                                   const std::string& where);

/// The file at `path` (read as input_file.h reads every user file).
ConfidenceCalibration read_confidence_calibration(const std::string& path);

/// The calibration built into lmk.
const ConfidenceCalibration& builtin_confidence_calibration();

}  // namespace lmk
