// SPDX-License-Identifier: BSD-3-Clause
// The confidence calibration file (confidence_calibration.h): read, refused when malformed, and
// applied as the logistic model it states.

#include "lmk/search/confidence/confidence_calibration.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "lmk/geometry/error.h"

namespace lmk {
namespace {

std::string calibration_text(const std::string& fields) {
  return R"({"format": "lmk-confidence-calibration", "version": 1, "metric": "visibility",
             "fitted_on": "a test", )" +
         fields + "}";
}

// The message of the lmk::Error that parsing `text` throws, or "" when it parses.
std::string refusal(const std::string& text) {
  try {
    parse_confidence_calibration(text, "cal.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ConfidenceCalibration, ReadsTheFormatItDocuments) {
  const ConfidenceCalibration c = parse_confidence_calibration(
      calibration_text(R"("bias": -1.5, "weights": {"local_margin": 0.5, "coverage": 2})"),
      "cal.json");
  EXPECT_EQ(c.metric, "visibility");
  EXPECT_EQ(c.fitted_on, "a test");
  EXPECT_DOUBLE_EQ(c.bias, -1.5);
  ASSERT_EQ(c.weights.size(), 2u);
  EXPECT_DOUBLE_EQ(c.weights.at("local_margin"), 0.5);
  EXPECT_DOUBLE_EQ(c.weights.at("coverage"), 2.0);
}

TEST(ConfidenceCalibration, RefusesWhatIsNotACalibrationNamingTheFile) {
  const std::string good_weights = R"("bias": 0, "weights": {"coverage": 1})";
  EXPECT_NE(refusal("not json").find("cal.json"), std::string::npos);
  EXPECT_NE(refusal(R"({"format": "lmk-landmark", "version": 1})").find("cal.json"),
            std::string::npos);
  // A newer version than this lmk reads.
  std::string newer = calibration_text(good_weights);
  newer.replace(newer.find("\"version\": 1"), 12, "\"version\": 2");
  EXPECT_NE(refusal(newer), "");
  EXPECT_NE(refusal(calibration_text(R"("bias": 0, "weights": {"colour": 1})")).find("colour"),
            std::string::npos);
  EXPECT_NE(refusal(calibration_text(R"("bias": "high", "weights": {})")), "");
  EXPECT_NE(refusal(calibration_text(R"("bias": 0, "weights": {"coverage": null})")), "");
  EXPECT_NE(refusal(calibration_text(R"("bias": 1e999, "weights": {})")), "");
  EXPECT_NE(refusal(calibration_text(R"("weights": {"coverage": 1})")), "");  // no bias
  EXPECT_EQ(refusal(calibration_text(good_weights)), "");
}

TEST(ConfidenceCalibration, IsTheLogisticModelOfItsFeatures) {
  ConfidenceCalibration c;
  c.metric = "visibility";
  c.bias = -1.0;
  c.weights = {{"coverage", 2.0}, {"local_margin", 0.5}};
  MatchConfidence m;
  m.coverage = 0.75;
  m.local_margin = 3.0;
  const double z = -1.0 + 2.0 * 0.75 + 0.5 * std::log1p(3.0);
  EXPECT_NEAR(calibrated_probability(m, c), 1.0 / (1.0 + std::exp(-z)), 1e-12);
  // A larger margin is never less sure; no rival at all counts as the cap, not as infinity.
  MatchConfidence clearer = m;
  clearer.local_margin = 12.0;
  EXPECT_GT(calibrated_probability(clearer, c), calibrated_probability(m, c));
  MatchConfidence unrivalled = m;
  unrivalled.local_margin = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(std::isfinite(calibrated_probability(unrivalled, c)));
  EXPECT_GE(calibrated_probability(unrivalled, c), calibrated_probability(clearer, c));
}

TEST(ConfidenceCalibration, AppliesOnlyToTheMetricItWasFittedFor) {
  const ConfidenceCalibration& builtin = builtin_confidence_calibration();
  EXPECT_EQ(calibration_for(builtin.metric, nullptr), &builtin);
  EXPECT_EQ(calibration_for("paper", nullptr), nullptr);
  MatchConfidence m;
  m.coverage = 1.0;
  calibrate(m, Box(), nullptr);
  EXPECT_TRUE(std::isnan(m.probability));
  calibrate(m, Box(), &builtin);
  EXPECT_GE(m.probability, 0.0);
  EXPECT_LE(m.probability, 1.0);
}

}  // namespace
}  // namespace lmk
