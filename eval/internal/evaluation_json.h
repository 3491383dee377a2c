// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The evaluation's own JSON (lmk eval --json, evaluation.json of a report, Python's lmk.evaluate):
// its dataset, settings, table rows and every pair; a pair's result is in pair_result_json.h,
// below it. Each report built on the evaluation writes its own JSON beside its code: the
// confidence's (risk_coverage_json.h), the explanation's (explanation_json.h), the ablation's
// (ablation_json.h). internal/: shared within lmk (the CLI, Python), not installed.

#include <nlohmann/json.hpp>
#include <vector>

#include "lmk/eval/evaluation.h"
#include "lmk/eval/evaluation_rows.h"
#include "lmk/eval/internal/pair_result_json.h"
#include "lmk/eval/internal/rows_json.h"

namespace lmk::detail {

/// {"method", "metric", "threshold", ..., "rows": [...], "pairs": [...]}: the issue's --json
/// schema, with the dataset, the settings and the run's times.
nlohmann::json evaluation_to_json(const Evaluation& evaluation,
                                  const std::vector<EvaluationRow>& rows);

}  // namespace lmk::detail
