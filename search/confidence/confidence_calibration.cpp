// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/confidence/confidence_calibration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "lmk/geometry/error.h"
#include "lmk/geometry/input_file.h"

namespace lmk {

extern const char* const kBuiltinConfidenceCalibration;  // landmark/data, compiled in by CMake

namespace {

// Beyond these the evidence says nothing more: a margin of 20 error sigmas is as sure as one of
// 200, and a logistic model that saw a few large values would otherwise let them dominate.
constexpr double kMarginCap = 20.0;
constexpr double kFitCap = 10.0;
constexpr double kRangeCap = 5.0;
constexpr double kLogFreedomBound = 3.0;
// A landmark's size is weighed as log10 of its box's diagonal over 10 cm, within +-1 (1 cm to 1 m).
constexpr double kSizeUnit = 0.1;

double capped(double v, double lo, double hi) {
  if (std::isnan(v)) return hi;
  return std::clamp(v, lo, hi);
}

// A margin's evidence grows with its logarithm: 1 sigma against 3 is much, 10 against 20 little.
// Signed: a rival that scores better (a negative margin) counts against the match alike.
double log_margin(double margin) {
  const double m = capped(margin, -kMarginCap, kMarginCap);
  return std::copysign(std::log1p(std::abs(m)), m);
}

// log10 of a distance over `unit`, within +-kLogFreedomBound: 0 and below the lower bound,
// +infinity the upper; NaN (not measured) 0.
double log_ratio(double distance, double unit) {
  const double ratio = distance / unit;
  if (std::isnan(ratio)) return 0.0;
  if (!(ratio > 0.0)) return -kLogFreedomBound;
  return capped(std::log10(ratio), -kLogFreedomBound, kLogFreedomBound);
}

// |log2| of the match's range over the capture's, within [0, 2]: 1 for a landmark seen from twice
// or half as far as it was captured; 0 unknown.
double range_change(double range, double capture_range) {
  const double ratio = range / capture_range;
  if (!(ratio > 0.0) || !std::isfinite(ratio)) return 0.0;
  return std::min(std::abs(std::log2(ratio)), 2.0);
}

}  // namespace

const std::vector<std::string>& confidence_feature_names() {
  static const std::vector<std::string> names = {"local_margin",
                                                 "elsewhere_margin",
                                                 "fit",
                                                 "coverage",
                                                 "log_freedom",
                                                 "range",
                                                 "intrusion",
                                                 "log_size",
                                                 "log_support",
                                                 "seen_fraction",
                                                 "capture_slide",
                                                 "capture_look_alike",
                                                 "capture_warned",
                                                 "range_change",
                                                 "view_change",
                                                 "local_margin_measured",
                                                 "elsewhere_margin_measured",
                                                 "fit_measured"};
  return names;
}

std::vector<double> confidence_features(const MatchConfidence& c) {
  const CaptureFindings& capture = c.capture;
  // Margins and fit from the model's units into the measured noise's (match_confidence.h).
  const double ratio = c.model_noise / c.measured_noise;
  const double to_measured = std::isfinite(ratio) && ratio > 0.0 ? ratio : 1.0;
  const double look_alike =
      !capture.look_alike_checked
          ? 0.0
          : (!capture.found_itself
                 ? 1.0
                 : (capture.look_alikes == 0 ? 0.0
                                             : 1.0 / std::max(1.0, capture.look_alike_ratio)));
  return {
      log_margin(c.local_margin),
      log_margin(c.elsewhere_margin),
      capped(c.fit, 0.0, kFitCap),
      std::isnan(c.coverage) ? 1.0 : c.coverage,
      log_ratio(c.freedom, kSamePoseDistance),
      capped(c.range, 0.0, kRangeCap),
      capped(c.intrusion, 0.0, 1.0),
      std::isnan(c.landmark_size) ? 0.0 : capped(std::log10(c.landmark_size / kSizeUnit), -1, 1),
      std::log10(static_cast<double>(std::clamp<std::size_t>(c.support, 1, 100000))),
      std::isnan(c.seen_fraction) ? 1.0 : capped(c.seen_fraction, 0.0, 1.0),
      capture.present ? log_ratio(capture.slide, kSamePoseDistance) : 0.0,
      look_alike,
      capture.present && capture.warned() ? 1.0 : 0.0,
      range_change(c.range, c.capture_range),
      std::isnan(c.view_change) ? 0.0 : capped(c.view_change, 0.0, M_PI),
      log_margin(c.local_margin * to_measured),
      log_margin(c.elsewhere_margin * to_measured),
      capped(c.fit * to_measured, 0.0, kFitCap)};
}

double calibrated_probability(const MatchConfidence& confidence,
                              const ConfidenceCalibration& calibration) {
  const std::vector<std::string>& names = confidence_feature_names();
  const std::vector<double> features = confidence_features(confidence);
  double logit = calibration.bias;
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto w = calibration.weights.find(names[k]);
    if (w != calibration.weights.end()) logit += w->second * features[k];
  }
  return 1.0 / (1.0 + std::exp(-logit));
}

const ConfidenceCalibration* calibration_for(const std::string& metric,
                                             const ConfidenceCalibration* chosen) {
  const ConfidenceCalibration& c = chosen ? *chosen : builtin_confidence_calibration();
  return c.metric == metric ? &c : nullptr;
}

void calibrate(MatchConfidence& confidence, const Box& box,
               const ConfidenceCalibration* calibration) {
  confidence.probability = calibration ? calibrated_probability(confidence, *calibration)
                                       : std::numeric_limits<double>::quiet_NaN();
  // No calibration weighs free space that nothing confirms: no data holds a robot acting there.
  if (confidence.free_space_unconfirmed) confidence.probability = 0.0;
  confidence.doubt = confidence.probability < 0.5 ? describe_doubt(confidence, box) : "";
}

ConfidenceCalibration parse_confidence_calibration(const std::string& text,
                                                   const std::string& where) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(where + ": not valid JSON (" + e.what() + ")");
  }
  const auto fail = [&](const std::string& problem) -> Error {
    return Error(where + ": " + problem +
                 " (a confidence calibration, as lmk calibrate-confidence writes it; "
                 "docs/file-formats.md)");
  };
  if (!j.is_object()) throw fail("must be a JSON object");
  const auto field = [&](const char* key) -> const nlohmann::json& {
    if (!j.contains(key)) throw fail(std::string("has no '") + key + "'");
    return j[key];
  };
  if (field("format") != "lmk-confidence-calibration")
    throw fail("'format' must be \"lmk-confidence-calibration\"");
  const nlohmann::json& version = field("version");
  if (!version.is_number_integer() || version.get<long long>() < 1) {
    throw fail("'version' must be a positive integer");
  }
  if (version.get<long long>() > kConfidenceCalibrationVersion) {
    throw fail("version " + version.dump() + " is newer than this lmk reads (" +
               std::to_string(kConfidenceCalibrationVersion) + "): update lmk");
  }
  ConfidenceCalibration c;
  const auto text_field = [&](const char* key) {
    const nlohmann::json& v = field(key);
    if (!v.is_string()) throw fail(std::string("'") + key + "' must be a string");
    return v.get<std::string>();
  };
  c.metric = text_field("metric");
  c.fitted_on = text_field("fitted_on");
  const nlohmann::json& bias = field("bias");
  if (!bias.is_number() || !std::isfinite(bias.get<double>()))
    throw fail("'bias' must be a finite number");
  c.bias = bias.get<double>();
  const nlohmann::json& weights = field("weights");
  if (!weights.is_object()) throw fail("'weights' must be an object of feature: weight");
  const std::vector<std::string>& names = confidence_feature_names();
  for (const auto& [name, w] : weights.items()) {
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      std::string known;
      for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
      throw fail("unknown feature '" + name + "' (known: " + known + ")");
    }
    if (!w.is_number() || !std::isfinite(w.get<double>()))
      throw fail("weights." + name + " must be a finite number");
    c.weights[name] = w.get<double>();
  }
  return c;
}

ConfidenceCalibration read_confidence_calibration(const std::string& path) {
  return parse_confidence_calibration(read_input_file(path, kJsonInput), path);
}

const ConfidenceCalibration& builtin_confidence_calibration() {
  static const ConfidenceCalibration builtin = parse_confidence_calibration(
      kBuiltinConfidenceCalibration, "lmk's built-in confidence calibration");
  return builtin;
}

}  // namespace lmk
