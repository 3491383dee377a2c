// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/internal/evaluation_document_json.h"

#include "lmk/eval/internal/evaluation_json.h"
#include "lmk/eval/internal/risk_coverage_json.h"

namespace lmk::detail {

nlohmann::json evaluation_document_to_json(const Evaluation& evaluation,
                                           const std::vector<EvaluationRow>& rows) {
  nlohmann::json json = evaluation_to_json(evaluation, rows);
  json["confidence"] = confidence_evaluation_to_json(evaluation);
  return json;
}

}  // namespace lmk::detail
