// SPDX-License-Identifier: BSD-3-Clause
// lmk eval [--dataset DIR | --preset NAME] [search options] [--pairs all|in-context]
//          [--threads N] [--json FILE] [--report DIR] [--cache DIR | --no-cache]
//          [--shard K/N | --merge] [--explain] [--no-capture-symmetry]
// The paper's precision/recall table of a search method on a dataset (docs/evaluation.md).

#include <cstdio>
#include <memory>

#include "lmk/datasets/benchmark_dataset.h"
#include "lmk/eval/evaluation.h"
#include "lmk/eval/evaluation_report.h"
#include "lmk/eval/evaluation_rows.h"
#include "lmk/eval/evaluation_table.h"
#include "lmk/eval/explain.h"
#include "lmk/eval/internal/evaluation_document_json.h"
#include "lmk/eval/internal/explanation_json.h"
#include "lmk/eval/internal/rows_json.h"
#include "lmk/eval/risk_coverage.h"
#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/error.h"
#include "tools/cli_common.h"
#include "tools/eval_common.h"
#include "tools/progress.h"

namespace lmk::cli {
namespace {

struct EvalOptions {
  DatasetOptions dataset;
  EvaluationSettings settings;
  std::string json, report;
  std::string by;     ///< "range", "hidden" or "views": also the table split by that
  std::string shard;  ///< --shard K/N
  bool merge = false;
  bool timings = false;
  bool explain = false;
  bool no_capture_symmetry = false;
};

// --explain: the cause of every miss and false match, as tables on stdout and in the JSON.
std::vector<ExplainedCase> explain(const LoadedDataset& data, const Evaluation& evaluation,
                                   const std::string& by) {
  ProgressBar bar("explain");
  const std::vector<ExplainedCase> cases =
      explain_evaluation(data.dir, data.dataset, evaluation,
                         [&bar](std::size_t done, std::size_t total) { bar.update(done, total); });
  const std::string& metric = evaluation.settings.find.selection.metric;
  std::printf(
      "\nwhy (each missed instance and false match in one cause; the metric at the true pose, "
      "aligned and polished from it, beside the wrong matches reported):\n\n%s",
      cause_table(cause_rows(cases), metric).plain().c_str());
  if (by == "range") {
    std::printf("\nwhy, by range:\n\n%s",
                cause_table(cause_rows(cases, 0.5), metric).plain().c_str());
  } else if (by == "hidden") {
    std::printf(
        "\nwhy, by the hidden fraction of each missed instance (false matches in \"all\" "
        "only):\n\n%s",
        cause_table(cause_rows_by_hidden(cases), metric).plain().c_str());
  }
  return cases;
}

// One line naming the pairs a merge lacks: the first few, and how many more.
std::string describe_missing(const Evaluation& e) {
  const std::size_t total = e.missing.size() + e.pairs.size();
  std::string names;
  constexpr std::size_t kNamed = 5;
  for (std::size_t i = 0; i < std::min(kNamed, e.missing.size()); ++i) {
    names += (i ? ", " : "") + e.missing[i].first + " x " + e.missing[i].second;
  }
  if (e.missing.size() > kNamed)
    names += ", and " + std::to_string(e.missing.size() - kNamed) + " more";
  return "merge: " + std::to_string(e.missing.size()) + " of " + std::to_string(total) +
         " pairs are not in the cache (" + names +
         "): run their shards again (each computes only what it lacks)";
}

int run_shard(const LoadedDataset& data, EvalOptions& o) {
  if (o.settings.cache_dir.empty()) {
    throw Error("--shard: a shard's results go into the cache, for --merge; --no-cache has none");
  }
  const Shard& shard = *o.settings.shard;
  const std::string label = "shard " + o.shard;
  const Evaluation evaluation = evaluate_with_progress(data, o.settings, label);
  std::printf(
      "%s: its %zu pairs are in the cache %s; once every shard of %d has run, lmk eval --merge "
      "with the same dataset and settings prints the table\n",
      label.c_str(), evaluation.pairs.size(), o.settings.cache_dir.c_str(), shard.count);
  return kOk;
}

int run_eval(EvalOptions& o) {
  if (!o.shard.empty()) o.settings.shard = parse_shard(o.shard);
  o.settings.cached_only = o.merge;
  o.settings.capture_symmetry = !o.no_capture_symmetry;
  const LoadedDataset data = load_or_generate(o.dataset, o.settings.cache_dir);
  if (o.settings.shard) return run_shard(data, o);
  const Evaluation evaluation =
      evaluate_with_progress(data, o.settings, o.merge ? "merge" : "eval");
  if (!evaluation.missing.empty()) throw Error(describe_missing(evaluation));
  const std::vector<EvaluationRow> rows = evaluation_rows(evaluation);
  std::printf("%s\n\n%s%s", evaluation_header(evaluation).c_str(),
              evaluation_table(rows, o.timings).plain().c_str(),
              capture_symmetry_note(evaluation).c_str());
  nlohmann::json json = detail::evaluation_document_to_json(evaluation, rows);
  // A split of the table, printed under its caption and kept in the JSON under `key`.
  const auto split = [&](const std::vector<EvaluationRow>& by, const char* caption,
                         const char* key) {
    std::printf("\n%s:\n\n%s", caption, evaluation_table(by, o.timings).plain().c_str());
    json[key] = detail::rows_to_json(by);
  };
  if (o.by == "range") {
    split(evaluation_rows_by_range(evaluation),
          "by range (distance from the sensor to each instance, or to a false match; a best match "
          "at its instance's)",
          "rows_by_range");
  } else if (o.by == "hidden") {
    split(evaluation_rows_by_hidden(evaluation),
          "by the hidden fraction of each instance (false matches in no row)", "rows_by_hidden");
  } else if (o.by == "views") {
    split(evaluation_rows_by_views(evaluation),
          "by the landmark's views and the azimuth from each instance, or false match, to the "
          "nearest of them",
          "rows_by_views");
  }
  std::printf("\n%s\n%s", risk_coverage_table(evaluation, o.by == "range").plain().c_str(),
              confidence_summary(evaluation).c_str());
  std::vector<ExplainedCase> explained;
  if (o.explain) {
    explained = explain(data, evaluation, o.by);
    json["explain"] = detail::explanation_to_json(explained);
  }
  if (!o.json.empty()) write_text_atomically(o.json, json_output(json, o.timings).dump(2) + "\n");
  if (!o.report.empty()) {
    write_evaluation_report(o.report, evaluation, data.dir, o.explain ? &explained : nullptr);
    // A message, on stderr: stdout holds the table alone, for files and comparisons.
    std::fprintf(stderr, "report: %s/report.html (also report.md, report.json)\n",
                 o.report.c_str());
  }
  return kOk;
}

}  // namespace

Subcommand add_eval(CLI::App& app) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* sub = app.add_subcommand(
      "eval",
      "Evaluate a search method on a dataset: the paper's precision/recall table per setting and "
      "assumption (default: the built-in 'paper' preset, fast method)");
  add_dataset_options(sub, o->dataset);
  add_search_options(sub, o->settings.find);
  add_evaluation_options(sub, o->settings);
  sub->add_option("--json", o->json, "Write the table and every pair's matches as JSON to FILE");
  add_timings_flag(sub, o->timings);
  sub->add_option("--by", o->by,
                  "Also split the table by 'range' (the distance from the sensor, 0.5 m bins), "
                  "'hidden' (the fraction of each instance the sensor does not see, 20% bins) or "
                  "'views' (the landmark's number of views, and the azimuth to the nearest, 15 "
                  "degree bins)")
      ->check(CLI::IsMember({"range", "hidden", "views"}));
  auto* shard = sub->add_option("--shard", o->shard,
                                "Evaluate only shard K of N (K/N): a stable share of the pairs, "
                                "for one machine of a cluster; results go into the cache");
  sub->add_flag("--merge", o->merge,
                "Print the table from the cache alone, searching nothing; names the pairs "
                "no shard has computed yet")
      ->excludes(shard);
  sub->add_flag("--explain", o->explain,
                "Put each missed instance and false match in one cause (no candidate near the "
                "truth, suppressed by a wrong one, over the threshold, coverage, empty space; a "
                "false match displacing the truth, off the pose, a look-alike), with the metric "
                "at the true pose: searches the failed pairs again")
      ->excludes(shard);
  sub->add_flag(
      "--no-capture-symmetry", o->no_capture_symmetry,
      "Count a pose turned about an axis the landmark's capture found symmetric as wrong, "
      "as the dataset alone says (by default it counts as right where the dataset gives "
      "the landmark no symmetry)");
  sub->add_option("--report", o->report,
                  "Write report.json, report.md and report.html (with plots) into DIR");
  return {sub, [o] { return run_eval(*o); }};
}

}  // namespace lmk::cli
