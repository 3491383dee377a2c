// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The paper's precision/recall table of an evaluation, as lmk eval prints it and reports hold it.

#include <string>
#include <vector>

#include "lmk/eval/evaluation.h"
#include "lmk/eval/evaluation_rows.h"
#include "lmk/eval/text_table.h"

namespace lmk {

/// One line per row: setting, assumption, precision, recall, TP/FP/FN, median translation (mm)
/// and rotation (degrees) errors of the true positives, median seconds per search.
/// Without `with_times`, the last column (wall time) is left out: the table is then the same
/// byte for byte for the same inputs and settings, whichever machines searched its pairs.
TextTable evaluation_table(const std::vector<EvaluationRow>& rows, bool with_times = true);

/// What the table measured, in one line: dataset, method, metric, threshold, seeds, pairs.
std::string evaluation_header(const Evaluation& evaluation);

/// Where the evaluation counted turns about an axis its capture found (issue #59,
/// EvaluationSettings::capture_symmetry), one line naming those landmarks and the rule's effect on
/// its own: the "all" rows' true positives with and without it, at the evaluation's threshold and
/// cut. Empty when no pair used it.
std::string capture_symmetry_note(const Evaluation& evaluation);

/// The assumption's name in the paper's terms: "1 all pairs", "2 in context", "3 best match".
std::string assumption_name(int assumption);

}  // namespace lmk
