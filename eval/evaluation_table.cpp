// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/evaluation_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lmk {

std::string assumption_name(int assumption) {
  switch (assumption) {
    case 1:
      return "1 all pairs";
    case 2:
      return "2 in context";
    default:
      return "3 best match";
  }
}

TextTable evaluation_table(const std::vector<EvaluationRow>& rows, bool with_times) {
  TextTable table;
  table.header = {"setting", "assumption", "precision", "recall",    "TP",      "FP",
                  "FN",      "pairs",      "t err mm",  "r err deg", "s/search"};
  table.numeric = {false, false, true, true, true, true, true, true, true, true, true};
  for (const EvaluationRow& r : rows) {
    table.rows.push_back(
        {r.setting, assumption_name(r.assumption), format_optional(r.counts.precision(), 3),
         format_optional(r.counts.recall(), 3), std::to_string(r.counts.tp),
         std::to_string(r.counts.fp), std::to_string(r.counts.fn), std::to_string(r.pairs),
         format_optional(r.median_translation_error, 1, 1e3),
         format_optional(r.median_rotation_error, 2, 180.0 / M_PI),
         format_optional(r.median_seconds, 3)});
  }
  if (!with_times) {
    table.header.pop_back();
    table.numeric.pop_back();
    for (auto& row : table.rows) row.pop_back();
  }
  return table;
}

std::string evaluation_header(const Evaluation& e) {
  const FindSettings& f = e.settings.find;  // resolved
  const std::string& metric = f.selection.metric;
  std::size_t scenes = 0;
  std::string last;
  for (const PairResult& p : e.pairs) {
    if (p.scene != last) ++scenes, last = p.scene;
  }
  char text[512];
  std::snprintf(text, sizeof(text),
                "dataset %s (%zu scenes, %zu pairs, %s pairs searched), method %s, metric %s, "
                "threshold %s, max seeds %zu; times per search on 1 thread",
                e.dataset.c_str(), scenes, e.pairs.size(),
                e.settings.in_context_only ? "in-context" : "all", setting_name(f.method).c_str(),
                metric.c_str(), format_error(*f.selection.threshold, metric).c_str(),
                *f.sampling.max_seeds);
  return text;
}

std::string capture_symmetry_note(const Evaluation& e) {
  std::vector<std::string> landmarks;
  for (const PairResult& p : e.pairs) {
    if (p.symmetry_from_capture &&
        std::find(landmarks.begin(), landmarks.end(), p.landmark) == landmarks.end())
      landmarks.push_back(p.landmark);
  }
  if (landmarks.empty()) return "";  // the common case: no copy of the evaluation
  Evaluation without = e;
  for (PairResult& p : without.pairs) {
    if (!p.symmetry_from_capture) continue;
    p.symmetry = Symmetry();
    p.symmetry_from_capture = false;
  }
  std::string names;
  for (const std::string& name : landmarks) names += (names.empty() ? "" : ", ") + name;
  const double threshold = *e.settings.find.selection.threshold;
  std::string effect;
  for (int assumption : {1, 3}) {
    if (assumption == 1 && e.settings.in_context_only) continue;
    const std::size_t with = evaluation_row(e, "all", assumption, threshold).counts.tp;
    const std::size_t plain = evaluation_row(without, "all", assumption, threshold).counts.tp;
    effect += (effect.empty() ? "" : ", ") + assumption_name(assumption) + " TP " +
              std::to_string(with) + " (" + std::to_string(plain) + " without it)";
  }
  return "symmetry found at capture, where the dataset gives none: " + names +
         " (a pose turned about its axis counts as right; --no-capture-symmetry leaves it out): " +
         effect + "\n";
}

}  // namespace lmk
