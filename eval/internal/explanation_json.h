// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// lmk eval --explain's diagnosis as JSON (explain.h). internal/: shared within lmk (the CLI, the
// report), not installed.

#include <nlohmann/json.hpp>
#include <vector>

#include "lmk/eval/explain.h"

namespace lmk::detail {

/// {"cases": [...], "by_setting": [...], "by_range": [...]}: every case with its cause and errors,
/// and the counts per cause.
nlohmann::json explanation_to_json(const std::vector<ExplainedCase>& cases);

}  // namespace lmk::detail
