// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The JSON forms of evaluation reports: the table rows and the settings, the ablation, the
// confidence's evaluation and the explanation; a pair's result is in pair_result_json.h, below
// them. internal/: shared within lmk (the CLI, Python), not installed: lmk's public headers never
// expose nlohmann-json.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lmk/eval/ablation.h"
#include "lmk/eval/evaluation.h"
#include "lmk/eval/explain.h"
#include "lmk/eval/internal/pair_result_json.h"

namespace lmk::detail {

nlohmann::json rows_to_json(const std::vector<EvaluationRow>& rows);

/// {"method", "metric", "threshold", ..., "rows": [...], "pairs": [...]}: the issue's --json
/// schema, with the dataset, the settings and the run's times.
nlohmann::json evaluation_to_json(const Evaluation& evaluation,
                                  const std::vector<EvaluationRow>& rows);

/// {"format": "lmk-ablation", ..., "variants": [{"values", "settings", "seconds", "rows"}]}: `lmk
/// ablate`'s ablation.json, and Python's lmk.ablate.
nlohmann::json ablation_to_json(const std::vector<AblationVariant>& variants,
                                const std::string& dataset);

/// {"pairs", "area", "at_precision_95", "at_precision_98", "curve": [{"cut", "answered",
/// "correct", "coverage", "precision"}...], "reliability": {"ece", "matches", "bins": [...]}}: how
/// the evaluation's confidences rank and how well calibrated they are (risk_coverage.h).
nlohmann::json confidence_evaluation_to_json(const Evaluation& evaluation);

/// {"cases": [...], "by_setting": [...], "by_range": [...]}: lmk eval --explain's diagnosis, every
/// case with its cause and errors, and the counts per cause.
nlohmann::json explanation_to_json(const std::vector<ExplainedCase>& cases);

}  // namespace lmk::detail
