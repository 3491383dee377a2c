// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The JSON form of one pair's result: the evaluation cache's file and the report's per-scene
// entries. The evaluation's core (evaluation.cpp, the pair cache) needs only this, not the
// reports above it and their JSON (internal/evaluation_json.h, explanation_json.h,
// ablation_json.h). internal/: shared within lmk, not installed: lmk's public headers never
// expose nlohmann-json.

#include <nlohmann/json.hpp>
#include <string>

#include "lmk/eval/evaluation.h"

namespace lmk::detail {

/// Each match says whether it is correct at `threshold` under `tolerance` (assumption 1's rule),
/// so the report's per-scene table needs no protocol code of its own.
nlohmann::json pair_result_to_json(const PairResult& pair, double threshold,
                                   const MatchTolerance& tolerance);
/// Reads what pair_result_to_json wrote; throws lmk::Error naming `where` for anything else.
PairResult pair_result_from_json(const nlohmann::json& j, const std::string& where);

}  // namespace lmk::detail
