// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The paper's precision/recall table of an evaluation, as lmk eval prints it and reports hold it.

#include <string>
#include <vector>

#include "lmk/eval/evaluation.h"
#include "lmk/eval/text_table.h"

namespace lmk {

/// One line per row: setting, assumption, precision, recall, TP/FP/FN, median translation (mm)
/// and rotation (degrees) errors of the true positives, median seconds per search.
TextTable evaluation_table(const std::vector<EvaluationRow>& rows);

/// What the table measured, in one line: dataset, method, metric, threshold, seeds, pairs.
std::string evaluation_header(const Evaluation& evaluation);

/// The assumption's name in the paper's terms: "1 all pairs", "2 in context", "3 best match".
std::string assumption_name(int assumption);

}  // namespace lmk
