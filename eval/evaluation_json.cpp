// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/internal/evaluation_json.h"

#include <cmath>

#include "lmk/eval/risk_coverage.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/version.h"
#include "lmk/json/box_json.h"
#include "lmk/landmark/internal/find_settings_json.h"

namespace lmk::detail {

using nlohmann::json;

namespace {

json optional_number(const std::optional<double>& v) {
  return v && std::isfinite(*v) ? json(*v) : json(nullptr);
}

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

json rows_to_json(const std::vector<EvaluationRow>& rows) {
  json out = json::array();
  for (const EvaluationRow& r : rows) {
    out.push_back({{"setting", r.setting},
                   {"assumption", r.assumption},
                   {"precision", optional_number(r.counts.precision())},
                   {"recall", optional_number(r.counts.recall())},
                   {"tp", r.counts.tp},
                   {"fp", r.counts.fp},
                   {"fn", r.counts.fn},
                   {"pairs", r.pairs},
                   {"median_translation_error_m", optional_number(r.median_translation_error)},
                   {"median_rotation_error_rad", optional_number(r.median_rotation_error)},
                   {"median_seconds_per_search", optional_number(r.median_seconds)}});
  }
  return out;
}

json evaluation_to_json(const Evaluation& e, const std::vector<EvaluationRow>& rows) {
  const FindSettings& f = e.settings.find;  // resolved
  const double threshold = *f.selection.threshold;
  json pairs = json::array();
  for (const PairResult& p : e.pairs)
    pairs.push_back(pair_result_to_json(p, threshold, e.settings.tolerance));
  return {{"format", "lmk-evaluation"},
          {"version", 1},
          {"lmk_version", kVersion},
          {"dataset", e.dataset},
          {"dataset_fingerprint", e.fingerprint},
          {"method", setting_name(f.method)},
          {"metric", f.selection.metric},
          {"threshold", threshold},
          {"max_seeds", *f.sampling.max_seeds},
          {"pairs_searched", e.settings.in_context_only ? "in-context" : "all"},
          {"tolerance",
           {{"translation_m", e.settings.tolerance.translation},
            {"rotation_rad", e.settings.tolerance.rotation}}},
          {"capture_symmetry", e.settings.capture_symmetry},
          {"settings", find_settings_to_json(f)},
          {"seconds", e.seconds},
          {"rows", rows_to_json(rows)},
          {"pairs", pairs}};
}

namespace {

json cause_rows_to_json(const std::vector<CauseRow>& rows) {
  json out = json::array();
  for (const CauseRow& r : rows) {
    json missed = json::object(), false_matches = json::object();
    for (std::size_t k = 0; k < r.missed.size(); ++k)
      missed[to_string(miss_causes()[k])] = r.missed[k];
    for (std::size_t k = 0; k < r.false_matches.size(); ++k)
      false_matches[to_string(false_match_causes()[k])] = r.false_matches[k];
    out.push_back(
        {{"group", r.group},
         {"missed", missed},
         {"false_matches", false_matches},
         {"median_error_at_truth", optional_number(r.median_truth_error)},
         {"median_error_of_wrong_winner", optional_number(r.median_winner_error)},
         {"median_confidence_of_wrong_winner", optional_number(r.median_winner_confidence)}});
  }
  return out;
}

}  // namespace

json explanation_to_json(const std::vector<ExplainedCase>& cases) {
  json list = json::array();
  for (const ExplainedCase& c : cases) {
    list.push_back({{"scene", c.scene},
                    {"landmark", c.landmark},
                    {"setting", c.setting},
                    {"kind", c.missed ? "missed" : "false match"},
                    {"cause", to_string(c.cause)},
                    {"box", box_to_json(c.box)},
                    {"range_m", c.range},
                    {"hidden", optional_number(c.hidden)},
                    {"error_at_truth", optional_number(c.truth_error)},
                    {"error_of_wrong_winner", optional_number(c.winner_error)},
                    {"confidence_of_wrong_winner", optional_number(c.winner_confidence)},
                    {"nearest_candidate_m", optional_number(c.nearest_candidate_translation)},
                    {"nearest_candidate_rad", optional_number(c.nearest_candidate_rotation)},
                    {"truth_drift_m", optional_number(c.truth_drift_translation)},
                    {"truth_drift_rad", optional_number(c.truth_drift_rotation)}});
  }
  json out = {{"cases", list},
              {"by_setting", cause_rows_to_json(cause_rows(cases))},
              {"by_range", cause_rows_to_json(cause_rows(cases, 0.5))}};
  if (std::any_of(cases.begin(), cases.end(), [](const ExplainedCase& c) { return c.hidden; }))
    out["by_hidden"] = cause_rows_to_json(cause_rows_by_hidden(cases));
  return out;
}

nlohmann::json ablation_to_json(const std::vector<AblationVariant>& variants,
                                const std::string& dataset) {
  nlohmann::json list = nlohmann::json::array();
  for (const AblationVariant& v : variants) {
    nlohmann::json values = nlohmann::json::object();
    for (const auto& [key, value] : v.values) values[key] = value;
    list.push_back({{"values", values},
                    {"settings", find_settings_to_json(v.evaluation.settings.find)},
                    {"seconds", v.evaluation.seconds},
                    {"rows", rows_to_json(v.rows)}});
  }
  return {{"format", "lmk-ablation"},
          {"version", 1},
          {"lmk_version", kVersion},
          {"dataset", dataset},
          {"dataset_fingerprint", variants.empty() ? "" : variants.front().evaluation.fingerprint},
          {"variants", list}};
}

}  // namespace lmk::detail
