// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/internal/evaluation_json.h"

#include "lmk/geometry/version.h"
#include "lmk/search/internal/find_settings_json.h"

namespace lmk::detail {

using nlohmann::json;

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

}  // namespace lmk::detail
