// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/ablation.h"

#include <algorithm>
#include <set>

#include "lmk/eval/evaluation_table.h"
#include "lmk/geometry/error.h"

namespace lmk {

std::vector<std::string> ablation_keys() { return find_setting_keys(true); }

void apply_ablation_setting(FindSettings& settings, const std::string& key,
                            const std::string& value) {
  const std::vector<std::string> varied = ablation_keys(), all = find_setting_keys();
  const auto has = [&key](const std::vector<std::string>& keys) {
    return std::find(keys.begin(), keys.end(), key) != keys.end();
  };
  if (!has(varied) && has(all))
    throw Error("--vary " + key + ": changes how a search runs, not what it finds");
  try {
    set_find_setting(settings, key, value);
  } catch (const Error& e) {
    throw Error("--vary " + key + "=" + value + ": " + e.what());
  }
}

AblationAxis parse_ablation_axis(const std::string& text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw Error("--vary '" + text + "': expected KEY=V1,V2,...");
  AblationAxis axis;
  axis.key = text.substr(0, eq);
  std::set<std::string> seen;
  std::size_t start = eq + 1;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string value = text.substr(start, comma - start);
    if (value.empty()) throw Error("--vary '" + text + "': an empty value");
    if (!seen.insert(value).second)
      throw Error("--vary '" + text + "': value '" + value + "' given twice");
    FindSettings probe;
    apply_ablation_setting(probe, axis.key, value);  // a bad key or value fails before any run
    axis.values.push_back(value);
    start = comma + 1;
  }
  return axis;
}

std::string AblationVariant::label() const {
  std::string out;
  for (const auto& [key, value] : values) out += (out.empty() ? "" : " ") + key + "=" + value;
  return out.empty() ? "(defaults)" : out;
}

std::vector<AblationVariant> run_ablation(
    const std::string& dir, const Dataset& dataset, const EvaluationSettings& base,
    const std::vector<AblationAxis>& axes,
    const std::function<void(std::size_t, std::size_t, const std::string&)>& on_variant) {
  std::set<std::string> keys;
  for (const AblationAxis& axis : axes) {
    if (!keys.insert(axis.key).second) throw Error("--vary " + axis.key + " is given twice");
  }
  // The grid, first axis slowest, as an odometer over the axes' value indices.
  std::vector<std::vector<std::pair<std::string, std::string>>> grid(1);
  for (const AblationAxis& axis : axes) {
    std::vector<std::vector<std::pair<std::string, std::string>>> next;
    for (const auto& partial : grid) {
      for (const std::string& value : axis.values) {
        next.push_back(partial);
        next.back().emplace_back(axis.key, value);
      }
    }
    grid = std::move(next);
  }
  std::vector<AblationVariant> variants;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    AblationVariant v;
    v.values = grid[i];
    EvaluationSettings settings = base;
    for (const auto& [key, value] : v.values) apply_ablation_setting(settings.find, key, value);
    if (on_variant) on_variant(i, grid.size(), v.label());
    try {
      v.evaluation = evaluate(dir, dataset, settings);
    } catch (const Interrupted& e) {
      throw Interrupted("variant " + std::to_string(i + 1) + " of " + std::to_string(grid.size()) +
                        " (" + v.label() + "): " + e.what());
    }
    v.rows = evaluation_rows(v.evaluation);
    variants.push_back(std::move(v));
  }
  return variants;
}

TextTable ablation_table(const std::vector<AblationVariant>& variants) {
  TextTable table;
  if (variants.empty()) return table;
  for (const auto& [key, value] : variants.front().values) table.header.push_back(key);
  const std::size_t keys = table.header.size();
  std::vector<int> assumptions;
  for (const EvaluationRow& r : variants.front().rows) {
    if (r.setting == "all") assumptions.push_back(r.assumption);
  }
  for (int a : assumptions) {
    table.header.push_back("P" + std::to_string(a));
    table.header.push_back("R" + std::to_string(a));
  }
  table.header.push_back("TP/FP/FN");  // of the first assumption evaluated
  table.header.push_back("s/search");
  table.numeric.assign(table.header.size(), true);
  for (std::size_t i = 0; i < keys; ++i) table.numeric[i] = false;
  for (const AblationVariant& v : variants) {
    std::vector<std::string> row;
    for (const auto& [key, value] : v.values) row.push_back(value);
    const EvaluationRow* first = nullptr;
    for (const EvaluationRow& r : v.rows) {
      if (r.setting != "all") continue;
      if (!first) first = &r;
      row.push_back(format_optional(r.counts.precision(), 3));
      row.push_back(format_optional(r.counts.recall(), 3));
    }
    row.push_back(first
                      ? std::to_string(first->counts.tp) + "/" + std::to_string(first->counts.fp) +
                            "/" + std::to_string(first->counts.fn)
                      : "-");
    row.push_back(first ? format_optional(first->median_seconds, 3) : "-");
    table.rows.push_back(row);
  }
  return table;
}

}  // namespace lmk
