// SPDX-License-Identifier: BSD-3-Clause
#include "tools/eval_common.h"

#include <cstdio>
#include <filesystem>

#include "lmk/datasets/benchmark_dataset.h"
#include "lmk/geometry/error.h"
#include "tools/cli_common.h"
#include "tools/interrupt.h"
#include "tools/progress.h"

namespace lmk::cli {

void add_dataset_options(CLI::App* sub, DatasetOptions& o) {
  std::string presets;
  for (const BenchmarkPreset& p : benchmark_presets())
    presets += (presets.empty() ? "" : ", ") + p.name;
  auto* dataset = sub->add_option("--dataset", o.dir, "Dataset directory (holding dataset.json)");
  sub->add_option("--preset", o.preset,
                  "Built-in benchmark, generated on first use: " + presets + " (default paper)")
      ->excludes(dataset);
  sub->add_option("--seeds", o.seeds,
                  "With a preset: scenes per scene type (1 to 1000; the paper's are 5 to 10)")
      ->check(CLI::Range(1, kMaxSeedsPerType))
      ->excludes(dataset);
  sub->add_flag("--hard", o.hard, "With a preset: its strong-rotation variants")->excludes(dataset);
  sub->add_option("--first-seed", o.first_seed,
                  "With a preset: its first scene seed (default 1), so that a method tuned on "
                  "some seeds is reported on others; 0 is the landmarks' demonstration scene")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1000000000}))
      ->excludes(dataset);
  sub->add_flag("--allow-outside-files", o.allow_outside_files,
                "With --dataset: read scene and landmark files that lie outside its directory "
                "(default: refused)")
      ->needs(dataset);
  sub->add_option("--types", o.types,
                  "With a preset: only these scene types (comma-separated, e.g. "
                  "simple/three_balls) and the landmarks in context in them")
      ->excludes(dataset);
}

void add_evaluation_options(CLI::App* sub, EvaluationSettings& s) {
  s.cache_dir = default_cache_dir();
  sub->add_option_function<std::string>(
         "--pairs", [&s](const std::string& v) { s.in_context_only = v == "in-context"; },
         "Pairs to search: all (assumptions 1-3) or in-context (assumptions 2 and 3)")
      ->check(CLI::IsMember({"all", "in-context"}))
      ->default_str("all");
  sub->add_option("--threads", s.threads, "Searches run at once (one thread each); 0: every core")
      ->check(worker_threads())
      ->capture_default_str();
  auto* cache = sub->add_option("--cache", s.cache_dir,
                                "Cache of generated datasets and of every search's result, so "
                                "that an interrupted run resumes")
                    ->capture_default_str();
  sub->add_flag_callback(
         "--no-cache", [&s] { s.cache_dir.clear(); }, "Search everything again, cache nothing")
      ->excludes(cache);
}

LoadedDataset load_or_generate(const DatasetOptions& o, const std::string& cache_dir) {
  LoadedDataset data;
  if (!o.dir.empty()) {
    data.dir = o.dir;
  } else {
    GenerateOptions generate;
    generate.seeds = o.seeds;
    generate.hard = o.hard;
    generate.first_seed = o.first_seed;
    generate.types = split_commas(o.types);
    const std::string preset = o.preset.empty() ? "paper" : o.preset;
    benchmark_preset(preset);  // an unknown name fails before anything else
    const std::string home = benchmark_dataset_home(cache_dir);
    std::fprintf(stderr, "dataset: preset '%s' (generated on first use into %s/datasets)\n",
                 preset.c_str(), home.c_str());
    ProgressBar bar("generate");  // draws only when the dataset is not cached yet
    generate.progress = [&bar](std::size_t done, std::size_t total) { bar.update(done, total); };
    data.dir = cached_benchmark_dataset(home, preset, generate);
  }
  data.dataset =
      load_dataset(data.dir, o.allow_outside_files ? DatasetFiles::anywhere : DatasetFiles::inside);
  return data;
}

Evaluation evaluate_with_progress(const LoadedDataset& data, EvaluationSettings settings,
                                  const std::string& label) {
  const Evaluation evaluation = [&] {
    ProgressBar bar(label);  // ends its line before the summary
    const StopOnSigint stop;
    settings.stop_requested = &StopOnSigint::requested;
    settings.progress = [&bar](std::size_t done, std::size_t total, std::size_t) {
      bar.update(done, total);
    };
    return evaluate(data.dir, data.dataset, settings);
  }();
  // A merge that lacks pairs is refused by its caller, in one line of its own.
  if (!evaluation.missing.empty()) return evaluation;
  std::size_t cached = 0;
  for (const PairResult& p : evaluation.pairs) cached += p.from_cache ? 1 : 0;
  std::fprintf(stderr, "%s: %zu pairs (%zu searched, %zu from the cache) in %.1f s\n",
               label.c_str(), evaluation.pairs.size(), evaluation.pairs.size() - cached, cached,
               evaluation.seconds);
  return evaluation;
}

}  // namespace lmk::cli
