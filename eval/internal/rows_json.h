// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The rows of the precision/recall table as JSON (evaluation_rows.h), which every report that
// prints the table writes: the evaluation, the ablation's variants, the report. internal/: shared
// within lmk (the CLI, Python), not installed: lmk's public headers never expose nlohmann-json.

#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "lmk/eval/evaluation_rows.h"

namespace lmk::detail {

/// A number, or null when absent or not finite: JSON has no NaN.
nlohmann::json optional_number(const std::optional<double>& v);

/// [{"setting", "assumption", "precision", "recall", "tp", "fp", "fn", "pairs",
///   "median_translation_error_m", "median_rotation_error_rad", "median_seconds_per_search"}...]
nlohmann::json rows_to_json(const std::vector<EvaluationRow>& rows);

}  // namespace lmk::detail
