// SPDX-License-Identifier: BSD-3-Clause
// Fitting the confidence calibration (eval/confidence_fit.h, `lmk calibrate-confidence`): on
// samples drawn from a known logistic model the fit finds that model, it refuses what cannot be
// fitted, and the file it writes is one the search reads.

#include "lmk/eval/confidence_fit.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "lmk/geometry/error.h"

namespace lmk {
namespace {

std::size_t column(const std::string& name) {
  const std::vector<std::string>& names = confidence_feature_names();
  return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
}

// Samples whose right-or-wrong is drawn from p = 1 / (1 + exp(-(bias + weight * coverage))).
std::vector<ConfidenceSample> drawn(double bias, double weight, std::size_t n) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<ConfidenceSample> out;
  for (std::size_t i = 0; i < n; ++i) {
    ConfidenceSample s;
    s.features.assign(confidence_feature_names().size(), 0.0);
    const double coverage = uniform(random);
    s.features[column("coverage")] = coverage;
    s.right = uniform(random) < 1.0 / (1.0 + std::exp(-(bias + weight * coverage)));
    out.push_back(s);
  }
  return out;
}

TEST(ConfidenceFit, FindsTheModelItsSamplesWereDrawnFrom) {
  ConfidenceFitSettings settings;
  settings.features = {"coverage"};
  settings.ridge = 0.0;
  const ConfidenceCalibration c =
      fit_confidence_calibration(drawn(-2.0, 4.0, 20000), settings, "visibility", "a test");
  EXPECT_NEAR(c.bias, -2.0, 0.15);
  ASSERT_EQ(c.weights.size(), 1u);
  EXPECT_NEAR(c.weights.at("coverage"), 4.0, 0.25);
  EXPECT_EQ(c.metric, "visibility");
  // The file it writes reads back as the same calibration.
  const ConfidenceCalibration read =
      parse_confidence_calibration(confidence_calibration_json(c), "fit.json");
  EXPECT_DOUBLE_EQ(read.bias, c.bias);
  EXPECT_DOUBLE_EQ(read.weights.at("coverage"), c.weights.at("coverage"));
  EXPECT_EQ(read.fitted_on, "a test");
}

TEST(ConfidenceFit, ARidgeKeepsAFeatureTheDataCannotFixNearZero) {
  ConfidenceFitSettings settings;
  settings.features = {"coverage", "range"};  // range is 0 in every sample: nothing fixes it
  const ConfidenceCalibration c =
      fit_confidence_calibration(drawn(-2.0, 4.0, 2000), settings, "visibility", "a test");
  EXPECT_NEAR(c.weights.at("range"), 0.0, 1e-6);
}

TEST(ConfidenceFit, RefusesWhatCannotBeFitted) {
  ConfidenceFitSettings settings;
  EXPECT_THROW(fit_confidence_calibration({}, settings, "visibility", ""), Error);
  std::vector<ConfidenceSample> all_right = drawn(10.0, 0.0, 50);
  for (ConfidenceSample& s : all_right) s.right = true;
  EXPECT_THROW(fit_confidence_calibration(all_right, settings, "visibility", ""), Error);
  settings.features = {"colour"};
  EXPECT_THROW(fit_confidence_calibration(drawn(0.0, 1.0, 50), settings, "visibility", ""), Error);
  settings.features = {};
  settings.ridge = -1.0;
  EXPECT_THROW(fit_confidence_calibration(drawn(0.0, 1.0, 50), settings, "visibility", ""), Error);
}

}  // namespace
}  // namespace lmk
