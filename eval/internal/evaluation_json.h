// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The JSON forms of evaluation results: a pair's result (the cache's file and the report's
// per-scene entries), the table rows and the settings. internal/: shared within lmk (the CLI,
// Python), not installed: lmk's public headers never expose nlohmann-json.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lmk/eval/ablation.h"
#include "lmk/eval/evaluation.h"
#include "lmk/eval/explain.h"

namespace lmk::detail {

nlohmann::json pair_result_to_json(const PairResult& pair, double threshold,
                                   const MatchTolerance& tolerance);
/// Reads what pair_result_to_json wrote; throws lmk::Error naming `where` for anything else.
PairResult pair_result_from_json(const nlohmann::json& j, const std::string& where);

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
