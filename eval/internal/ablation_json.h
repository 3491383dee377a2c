// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// An ablation as JSON (ablation.h): `lmk ablate`'s ablation.json, and Python's lmk.ablate.
// internal/: shared within lmk, not installed.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lmk/eval/ablation.h"

namespace lmk::detail {

/// {"format": "lmk-ablation", ..., "variants": [{"values", "settings", "seconds", "rows"}]}.
nlohmann::json ablation_to_json(const std::vector<AblationVariant>& variants,
                                const std::string& dataset);

}  // namespace lmk::detail
