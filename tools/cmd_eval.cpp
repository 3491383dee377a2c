// SPDX-License-Identifier: BSD-3-Clause
// lmk eval [--dataset DIR | --preset NAME] [search options] [--pairs all|in-context]
//          [--threads N] [--json FILE] [--report DIR] [--cache DIR | --no-cache]
// The paper's precision/recall table of a search method on a dataset (docs/evaluation.md).

#include <cstdio>
#include <memory>

#include "lmk/eval/benchmark_dataset.h"
#include "lmk/eval/detail/evaluation_json.h"
#include "lmk/eval/evaluation.h"
#include "lmk/eval/evaluation_report.h"
#include "lmk/eval/evaluation_table.h"
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
  std::string by;  ///< "range" or "hidden": also the table split by that
  bool timings = false;
};

int run_eval(EvalOptions& o) {
  const LoadedDataset data = load_or_generate(o.dataset, o.settings.cache_dir);
  const Evaluation evaluation = evaluate_with_progress(data, o.settings, "eval");
  const std::vector<EvaluationRow> rows = evaluation_rows(evaluation);
  std::printf("%s\n\n%s", evaluation_header(evaluation).c_str(),
              evaluation_table(rows).plain().c_str());
  nlohmann::json json = detail::evaluation_to_json(evaluation, rows);
  if (o.by == "range") {
    const std::vector<EvaluationRow> by_range = evaluation_rows_by_range(evaluation);
    std::printf(
        "\nby range (distance from the sensor to each instance, or to a false match):\n\n%s",
        evaluation_table(by_range).plain().c_str());
    json["rows_by_range"] = detail::rows_to_json(by_range);
  } else if (o.by == "hidden") {
    const std::vector<EvaluationRow> by_hidden = evaluation_rows_by_hidden(evaluation);
    std::printf("\nby the hidden fraction of each instance (false matches in no row):\n\n%s",
                evaluation_table(by_hidden).plain().c_str());
    json["rows_by_hidden"] = detail::rows_to_json(by_hidden);
  }
  if (!o.json.empty()) write_text_atomically(o.json, json_output(json, o.timings).dump(2) + "\n");
  if (!o.report.empty()) {
    write_evaluation_report(o.report, evaluation, data.dir);
    std::printf("report: %s/report.html (also report.md, report.json)\n", o.report.c_str());
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
                  "Also split the table by 'range' (the distance from the sensor, 0.5 m bins) or "
                  "'hidden' (the fraction of each instance the sensor does not see, 20% bins)")
      ->check(CLI::IsMember({"range", "hidden"}));
  sub->add_option("--report", o->report,
                  "Write report.json, report.md and report.html (with plots) into DIR");
  return {sub, [o] { return run_eval(*o); }};
}

}  // namespace lmk::cli
