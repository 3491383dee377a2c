// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The confidence's evaluation as JSON (risk_coverage.h): how the evaluation's confidences rank and
// how well calibrated they are. internal/: shared within lmk (the CLI), not installed.

#include <nlohmann/json.hpp>

#include "lmk/eval/evaluation.h"

namespace lmk::detail {

/// {"pairs", "area", "at_precision_95", "at_precision_98", "curve": [{"cut", "answered",
/// "correct", "coverage", "precision"}...], "reliability": {"ece", "matches", "bins": [...]}}.
nlohmann::json confidence_evaluation_to_json(const Evaluation& evaluation);

}  // namespace lmk::detail
