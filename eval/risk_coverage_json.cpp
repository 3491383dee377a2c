// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/internal/risk_coverage_json.h"

#include "lmk/eval/risk_coverage.h"

namespace lmk::detail {

using nlohmann::json;

namespace {

json point_to_json(const RiskCoveragePoint& p) {
  return {{"cut", p.cut},
          {"answered", p.answered},
          {"correct", p.correct},
          {"coverage", p.coverage},
          {"precision", p.answered ? json(p.precision) : json(nullptr)}};
}

json optional_point(const std::optional<RiskCoveragePoint>& p) {
  return p ? point_to_json(*p) : json(nullptr);
}

}  // namespace

json confidence_evaluation_to_json(const Evaluation& e) {
  const RiskCoverage curve = risk_coverage(e);
  json points = json::array();
  for (const RiskCoveragePoint& p : curve.curve) points.push_back(point_to_json(p));
  const Reliability r = reliability(e);
  json bins = json::array();
  for (const ReliabilityBin& b : r.bins) {
    bins.push_back({{"low", b.low},
                    {"high", b.high},
                    {"matches", b.matches},
                    {"predicted", b.matches ? json(b.predicted) : json(nullptr)},
                    {"observed", b.matches ? json(b.observed) : json(nullptr)}});
  }
  return {{"pairs", curve.pairs},
          {"area", curve.area},
          {"at_precision_95", optional_point(curve.at_95)},
          {"at_precision_98", optional_point(curve.at_98)},
          {"curve", points},
          {"reliability", {{"ece", r.ece}, {"matches", r.matches}, {"bins", bins}}}};
}

}  // namespace lmk::detail
