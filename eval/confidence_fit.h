// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Fitting the confidence calibration (search/confidence/confidence_calibration.h) on labelled
// searches (issue #59): every match an evaluation found below its threshold in an in-context pair
// is a sample, its features as the search computed them and whether the protocol counts it right. A
// logistic model with a small ridge (a feature the data cannot fix stays near 0) is fitted by
// Newton's method. `lmk calibrate-confidence` runs it; a team refits for its own robot with it.

#include <string>
#include <vector>

#include "lmk/eval/evaluation.h"
#include "lmk/search/confidence/confidence_calibration.h"

namespace lmk {

struct ConfidenceSample {
  std::vector<double> features;  ///< confidence_features(), in confidence_feature_names() order
  bool right = false;            ///< the protocol assigns it to a true instance
  bool best = false;             ///< its pair's best match
  bool unconfirmed = false;      ///< free space nothing confirms: probability 0 whatever the fit
};

/// The samples of `evaluation`: every match for_each_counted_match() visits (eval/risk_coverage.h),
/// as reliability() counts them.
std::vector<ConfidenceSample> confidence_samples(const Evaluation& evaluation);

struct ConfidenceFitSettings {
  /// The features to weigh (confidence_feature_names()); empty: every one.
  std::vector<std::string> features;
  /// Ridge on every weight but the bias: keeps a feature the data cannot fix near 0.
  double ridge = 1.0;
};

/// The logistic calibration of `samples` for `metric`, described by `fitted_on`. Throws lmk::Error
/// for no samples, samples all right or all wrong (nothing to tell apart), an unknown feature, or
/// a negative ridge.
ConfidenceCalibration fit_confidence_calibration(const std::vector<ConfidenceSample>& samples,
                                                 const ConfidenceFitSettings& settings,
                                                 const std::string& metric,
                                                 const std::string& fitted_on);

/// Every found box's probability (and doubt) in `evaluation` recomputed under `calibration`, as a
/// search with it would have set them: the tables and the risk-coverage curve then read them.
void recalibrate(Evaluation& evaluation, const ConfidenceCalibration& calibration);

/// The calibration as its file holds it (docs/file-formats.md, "Confidence calibration").
std::string confidence_calibration_json(const ConfidenceCalibration& calibration);

}  // namespace lmk
