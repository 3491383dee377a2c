// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/internal/explanation_json.h"

#include <algorithm>

#include "lmk/eval/internal/rows_json.h"
#include "lmk/json/box_json.h"

namespace lmk::detail {

using nlohmann::json;

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

}  // namespace lmk::detail
