#include "eval/ablation.h"

#include <cmath>
#include <map>
#include <set>

#include "eval/evaluation_table.h"
#include "geometry/error.h"

namespace lmk {

namespace {

double parse_number(const std::string& key, const std::string& value) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != value.size() || !std::isfinite(v))
    throw Error("--vary " + key + ": '" + value + "' is not a number");
  return v;
}

double positive(const std::string& key, const std::string& value) {
  const double v = parse_number(key, value);
  if (!(v > 0.0)) throw Error("--vary " + key + ": '" + value + "' must be positive");
  return v;
}

std::size_t count(const std::string& key, const std::string& value) {
  const double v = positive(key, value);
  if (v != std::floor(v)) throw Error("--vary " + key + ": '" + value + "' must be an integer");
  return static_cast<std::size_t>(v);
}

double fraction(const std::string& key, const std::string& value) {
  const double v = parse_number(key, value);
  if (v < 0.0 || v > 1.0) throw Error("--vary " + key + ": '" + value + "' must be in [0, 1]");
  return v;
}

using Setter = std::function<void(FindSettings&, const std::string&, const std::string&)>;

const std::map<std::string, Setter>& setters() {
  static const std::map<std::string, Setter> all = {
      {"method",
       [](FindSettings& s, const std::string& k, const std::string& v) {
         const auto methods = search_methods();
         if (std::find(methods.begin(), methods.end(), v) == methods.end())
           throw Error("--vary " + k + ": unknown method '" + v + "'");
         s.method = v;
       }},
      {"metric",
       [](FindSettings& s, const std::string&, const std::string& v) {
         find_error_metric(v);  // lists the known metrics for an unknown one
         s.metric = v;
       }},
      {"threshold", [](FindSettings& s, const std::string& k,
                       const std::string& v) { s.threshold = positive(k, v); }},
      {"max-seeds", [](FindSettings& s, const std::string& k,
                       const std::string& v) { s.max_seeds = count(k, v); }},
      {"seeds-per-instance", [](FindSettings& s, const std::string& k,
                                const std::string& v) { s.seeds_per_instance = positive(k, v); }},
      {"seed",
       [](FindSettings& s, const std::string& k, const std::string& v) {
         const double n = parse_number(k, v);
         if (n < 0 || n != std::floor(n)) throw Error("--vary seed: '" + v + "' must be >= 0");
         s.seed = static_cast<std::uint64_t>(n);
       }},
      {"orientations",
       [](FindSettings& s, const std::string& k, const std::string& v) {
         if (v != "upright" && v != "full")
           throw Error("--vary " + k + ": '" + v + "' must be upright or full");
         s.orientations = v;
       }},
      {"max-tilt", [](FindSettings& s, const std::string& k,
                      const std::string& v) { s.max_tilt = positive(k, v) * M_PI / 180.0; }},
      {"min-coverage", [](FindSettings& s, const std::string& k,
                          const std::string& v) { s.min_coverage = fraction(k, v); }},
      {"max-empty-violation",
       [](FindSettings& s, const std::string& k, const std::string& v) {
         s.max_empty_space_violation = fraction(k, v);
       }},
      {"leaf", [](FindSettings& s, const std::string& k,
                  const std::string& v) { s.leaf_size = positive(k, v); }},
      {"coarse-leaf", [](FindSettings& s, const std::string& k,
                         const std::string& v) { s.coarse_leaf = positive(k, v); }},
      {"nms-radius", [](FindSettings& s, const std::string& k,
                        const std::string& v) { s.nms_radius = positive(k, v); }},
      {"max-candidates", [](FindSettings& s, const std::string& k,
                            const std::string& v) { s.max_candidates = count(k, v); }},
      {"refine",
       [](FindSettings& s, const std::string& k, const std::string& v) {
         if (v != "true" && v != "false")
           throw Error("--vary " + k + ": '" + v + "' must be true or false");
         s.refine = v == "true";
       }},
  };
  return all;
}

}  // namespace

std::vector<std::string> ablation_keys() {
  std::vector<std::string> keys;
  for (const auto& [key, setter] : setters()) keys.push_back(key);
  return keys;
}

void apply_ablation_setting(FindSettings& settings, const std::string& key,
                            const std::string& value) {
  const auto it = setters().find(key);
  if (it == setters().end()) {
    std::string known;
    for (const std::string& k : ablation_keys()) known += (known.empty() ? "" : ", ") + k;
    throw Error("--vary: unknown setting '" + key + "' (known: " + known + ")");
  }
  it->second(settings, key, value);
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
    v.evaluation = evaluate(dir, dataset, settings);
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
