// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What every writer of an evaluation writes (lmk eval --json, a report's report.json, Python's
// lmk.eval): the evaluation's own JSON (evaluation_json.h) and the reports computed from the
// evaluation alone: today the confidence's (risk_coverage_json.h), under "confidence". A new report
// that needs nothing but the evaluation joins here, and so reaches all three. Reports that cost
// more (the explanation) stay behind their own flag. internal/: shared within lmk, not installed.

#include <nlohmann/json.hpp>
#include <vector>

#include "lmk/eval/evaluation.h"
#include "lmk/eval/evaluation_rows.h"

namespace lmk::detail {

/// evaluation_to_json(evaluation, rows) with "confidence" (confidence_evaluation_to_json).
nlohmann::json evaluation_document_to_json(const Evaluation& evaluation,
                                           const std::vector<EvaluationRow>& rows);

}  // namespace lmk::detail
