// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Ablations: the evaluation of every combination of a few search settings over one dataset, and
// one table comparing them. Each variant is an ordinary evaluation, so each resumes from the
// cache on its own and reuses any variant an earlier ablation or evaluation already ran.

#include <functional>
#include <string>
#include <vector>

#include "lmk/eval/evaluation.h"
#include "lmk/eval/evaluation_rows.h"
#include "lmk/eval/text_table.h"

namespace lmk {

/// One setting varied, with its values as written on the command line ("metric", {"paper",
/// "vdb"}).
struct AblationAxis {
  std::string key;
  std::vector<std::string> values;
};

/// Parses "KEY=V1,V2,...". Throws lmk::Error naming the known keys for an unknown one, and for
/// an empty or repeated value.
AblationAxis parse_ablation_axis(const std::string& text);

/// The keys that can be varied: every search setting, by its flag's name (find_setting_keys():
/// method, metric, threshold, max-seeds, max-tilt in degrees, refine true/false, ...).
std::vector<std::string> ablation_keys();

/// Sets `key` to `value` in `settings`; throws lmk::Error for a value that does not parse or is
/// out of range.
void apply_ablation_setting(FindSettings& settings, const std::string& key,
                            const std::string& value);

struct AblationVariant {
  std::vector<std::pair<std::string, std::string>> values;  ///< key, value: one per axis
  Evaluation evaluation;
  std::vector<EvaluationRow> rows;
  std::string label() const;  ///< "metric=paper method=fast"
};

/// Evaluates every combination of the axes' values (the first axis varying slowest), starting
/// from `base`. `on_variant` is called before each variant with (index, count, label).
std::vector<AblationVariant> run_ablation(
    const std::string& dir, const Dataset& dataset, const EvaluationSettings& base,
    const std::vector<AblationAxis>& axes,
    const std::function<void(std::size_t, std::size_t, const std::string&)>& on_variant = {});

/// One line per variant: its values, then precision and recall over all settings under each
/// assumption evaluated, and the median seconds per search.
TextTable ablation_table(const std::vector<AblationVariant>& variants);

}  // namespace lmk
