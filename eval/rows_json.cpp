// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/internal/rows_json.h"

#include <cmath>

namespace lmk::detail {

using nlohmann::json;

json optional_number(const std::optional<double>& v) {
  return v && std::isfinite(*v) ? json(*v) : json(nullptr);
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

}  // namespace lmk::detail
