// SPDX-License-Identifier: BSD-3-Clause
// lmk ablate [--dataset DIR | --preset NAME] --vary KEY=V1,V2,... [--vary ...] [search options]
//            [--pairs all|in-context] [--threads N] [--out DIR] [--cache DIR | --no-cache]
// Every combination of the varied settings, evaluated and compared in one table.

#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "lmk/eval/ablation.h"
#include "lmk/eval/evaluation_table.h"
#include "lmk/eval/internal/ablation_json.h"
#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/version.h"
#include "lmk/search/internal/find_settings_json.h"
#include "tools/cli_common.h"
#include "tools/eval_common.h"
#include "tools/interrupt.h"
#include "tools/progress.h"

namespace lmk::cli {
namespace {

namespace fs = std::filesystem;

struct AblateOptions {
  DatasetOptions dataset;
  EvaluationSettings settings;
  std::vector<std::string> vary;
  std::string out = "lmk-ablation";
  bool timings = false;
};

int run_ablate(AblateOptions& o) {
  std::vector<AblationAxis> axes;
  for (const std::string& text : o.vary) axes.push_back(parse_ablation_axis(text));
  const LoadedDataset data = load_or_generate(o.dataset, o.settings.cache_dir);
  std::unique_ptr<ProgressBar> bar;
  o.settings.progress = [&bar](std::size_t done, std::size_t total, std::size_t) {
    if (bar) bar->update(done, total);
  };
  const StopOnSigint stop;
  o.settings.stop_requested = &StopOnSigint::requested;
  const std::vector<AblationVariant> variants =
      run_ablation(data.dir, data.dataset, o.settings, axes,
                   [&bar](std::size_t i, std::size_t n, const std::string& label) {
                     bar.reset();  // ends the previous variant's line
                     std::fprintf(stderr, "variant %zu/%zu: %s\n", i + 1, n, label.c_str());
                     bar = std::make_unique<ProgressBar>("  pairs");
                   });
  bar.reset();
  const TextTable table = ablation_table(variants);
  const std::string header = "ablation on dataset " + data.dataset.name + " (" +
                             std::to_string(variants.size()) + " variants, " +
                             (o.settings.in_context_only ? "in-context" : "all") +
                             " pairs; P/R over all settings per assumption; times per search on "
                             "1 thread)";
  std::printf("%s\n\n%s", header.c_str(), table.plain().c_str());
  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (ec) throw Error(o.out + ": cannot create the output directory (" + ec.message() + ")");
  write_text_atomically(
      fs::path(o.out) / "ablation.json",
      json_output(detail::ablation_to_json(variants, data.dataset.name), o.timings).dump(2) + "\n");
  write_text_atomically(fs::path(o.out) / "ablation.md",
                        "# lmk ablation\n\n" + header + ".\n\n" + table.markdown());
  std::printf("wrote %s/ablation.json and %s/ablation.md\n", o.out.c_str(), o.out.c_str());
  return kOk;
}

}  // namespace

Subcommand add_ablate(CLI::App& app) {
  auto o = std::make_shared<AblateOptions>();
  std::string keys;
  for (const std::string& k : ablation_keys()) keys += (keys.empty() ? "" : ", ") + k;
  CLI::App* sub = app.add_subcommand(
      "ablate",
      "Evaluate every combination of varied search settings on a dataset and compare them in "
      "one table (resumes from the cache)");
  sub->add_option("--vary", o->vary, "KEY=V1,V2,... (repeatable); keys: " + keys)->required();
  add_dataset_options(sub, o->dataset);
  add_search_options(sub, o->settings.find);
  add_evaluation_options(sub, o->settings);
  sub->add_option("--out", o->out, "Directory for ablation.json and ablation.md")
      ->capture_default_str();
  add_timings_flag(sub, o->timings);
  return {sub, [o] { return run_ablate(*o); }};
}

}  // namespace lmk::cli
