// SPDX-License-Identifier: BSD-3-Clause
// The risk-coverage curve and the reliability of confidences (risk_coverage.h) on a table of
// results built by hand, where every figure can be counted on one's fingers.

#include "lmk/eval/risk_coverage.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lmk/geometry/pose.h"

namespace lmk {
namespace {

// One in-context pair whose instance stands at x = `range` in front of the sensor at the origin;
// its best match lies on the instance when `right`, 30 cm beside it otherwise, with confidence
// `probability`.
PairResult pair(const std::string& scene, double range, bool right, double probability) {
  PairResult p;
  p.scene = scene;
  p.landmark = "cup";
  p.setting = "table";
  p.in_context = true;
  p.truth = {pose_from_xyz_rpy({range, 0, 0}, {0, 0, 0})};
  FoundBox found;
  found.box = Box(pose_from_xyz_rpy({range, right ? 0.0 : 0.3, 0}, {0, 0, 0}), {0.1, 0.1, 0.1});
  found.error = 0.002;
  found.confidence.probability = probability;
  p.found = {found};
  return p;
}

// Six pairs, best matches by falling confidence: right, right, wrong, right, wrong, wrong; two of
// them beyond 2 m.
Evaluation six_pairs() {
  Evaluation e;
  e.settings.find = FindSettings().resolved();
  e.dataset = "hand";
  e.pairs = {pair("a", 1.0, true, 0.95), pair("b", 1.5, true, 0.9),  pair("c", 1.2, false, 0.8),
             pair("d", 2.5, true, 0.6),  pair("e", 2.4, false, 0.3), pair("f", 1.1, false, 0.1)};
  return e;
}

TEST(RiskCoverage, TheCurveCountsTheAnswersAsTheCutFalls) {
  const RiskCoverage r = risk_coverage(six_pairs());
  EXPECT_EQ(r.pairs, 6u);
  ASSERT_EQ(r.curve.size(), 6u);
  const std::vector<std::size_t> correct = {1, 2, 2, 3, 3, 3};
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(r.curve[k].answered, k + 1);
    EXPECT_EQ(r.curve[k].correct, correct[k]);
    EXPECT_NEAR(r.curve[k].coverage, (k + 1) / 6.0, 1e-12);
    EXPECT_NEAR(r.curve[k].precision, correct[k] / (k + 1.0), 1e-12);
  }
  EXPECT_DOUBLE_EQ(r.curve.front().cut, 0.95);
  // Precision 0.95 and 0.98 hold only for the two surest answers.
  ASSERT_TRUE(r.at_95 && r.at_98);
  EXPECT_EQ(r.at_95->answered, 2u);
  EXPECT_DOUBLE_EQ(r.at_95->cut, 0.9);
  EXPECT_EQ(r.at_98->answered, 2u);
  EXPECT_GT(r.area, 0.0);
  EXPECT_LT(r.area, 1.0);
}

TEST(RiskCoverage, ThePointAtACutAndByRange) {
  const Evaluation e = six_pairs();
  const RiskCoverage all = risk_coverage(e);
  const RiskCoveragePoint at = risk_coverage_at(all, 0.8);
  EXPECT_EQ(at.answered, 3u);
  EXPECT_EQ(at.correct, 2u);
  EXPECT_EQ(risk_coverage_at(all, 0.99).answered, 0u);
  const RiskCoverage near = risk_coverage(e, instance_range_within(0.0, 2.0));
  EXPECT_EQ(near.pairs, 4u);
  EXPECT_EQ(risk_coverage_at(near, 0.8).answered, 3u);
  const RiskCoverage far = risk_coverage(e, instance_range_within(2.0, 3.0));
  EXPECT_EQ(far.pairs, 2u);
  EXPECT_EQ(risk_coverage_at(far, 0.5).answered, 1u);
  EXPECT_EQ(risk_coverage_at(far, 0.5).correct, 1u);
}

// Issue #59: the table by landmark size selects each pair by its landmark's capture box.
TEST(RiskCoverage, ThePointAtACutByLandmarkSize) {
  Evaluation e = six_pairs();
  for (std::size_t k = 0; k < e.pairs.size(); ++k) e.pairs[k].landmark_size = k < 3 ? 0.15 : 0.5;
  const RiskCoverage small = risk_coverage(e, landmark_size_within(0.1, 0.2));
  const RiskCoverage large = risk_coverage(e, landmark_size_within(0.4, 1e9));
  EXPECT_EQ(small.pairs, 3u);
  EXPECT_EQ(large.pairs, 3u);
  // At 0.85 the small landmarks answer their two right best matches, the large none.
  EXPECT_EQ(risk_coverage_at(small, 0.85).answered, 2u);
  EXPECT_EQ(risk_coverage_at(small, 0.85).correct, 2u);
  EXPECT_EQ(risk_coverage_at(large, 0.85).answered, 0u);
  EXPECT_EQ(risk_coverage(e, landmark_size_within(0.2, 0.4)).pairs, 0u);
  const std::string table = risk_coverage_table(e, true).plain();
  EXPECT_NE(table.find("landmark box diagonal 10-20 cm"), std::string::npos) << table;
  EXPECT_NE(table.find("landmark box diagonal 40+ cm"), std::string::npos) << table;
}

TEST(RiskCoverage, ReliabilityAndCalibrationErrorOfTheProbabilities) {
  const Reliability r = reliability(six_pairs());
  EXPECT_EQ(r.matches, 6u);
  ASSERT_EQ(r.bins.size(), 10u);
  // 0.9 and 0.95 share the top bin, both right: predicted 0.925, observed 1.
  EXPECT_EQ(r.bins[9].matches, 2u);
  EXPECT_NEAR(r.bins[9].predicted, 0.925, 1e-12);
  EXPECT_NEAR(r.bins[9].observed, 1.0, 1e-12);
  // Each bin's gap weighted by its share: (2 x 0.075 + 0.8 + 0.4 + 0.3 + 0.1) / 6.
  EXPECT_NEAR(r.ece, (2 * 0.075 + 0.8 + 0.4 + 0.3 + 0.1) / 6.0, 1e-12);
  // A match without a probability (no calibration for its metric) is left out.
  Evaluation e = six_pairs();
  e.pairs[0].found[0].confidence.probability = std::nan("");
  EXPECT_EQ(reliability(e).matches, 5u);
}

}  // namespace
}  // namespace lmk
