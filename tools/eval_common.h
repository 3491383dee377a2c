// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What lmk eval and lmk ablate share: choosing the dataset (a directory, or a built-in preset
// generated once into the cache), the evaluation options, and a run with progress.

#include <cstdint>
#include <string>

#include "lmk/datasets/benchmark_dataset.h"
#include "lmk/eval/evaluation.h"
#include "tools/cli_common.h"

namespace lmk::cli {

struct DatasetOptions {
  std::string dir;                   ///< --dataset
  std::string preset;                ///< --preset (default "paper" when neither is given)
  std::optional<int> seeds;          ///< --seeds, with a preset
  bool hard = false;                 ///< --hard, with a preset
  std::uint64_t first_seed = 1;      ///< --first-seed, with a preset
  std::string types;                 ///< --types, with a preset: comma-separated scene types
  bool allow_outside_files = false;  ///< --allow-outside-files, with --dataset
};
void add_dataset_options(CLI::App* sub, DatasetOptions& options);

/// --pairs all|in-context, --threads, --cache DIR, --no-cache (settings.cache_dir starts as
/// default_cache_dir()).
void add_evaluation_options(CLI::App* sub, EvaluationSettings& settings);

struct LoadedDataset {
  std::string dir;
  Dataset dataset;
};
/// The dataset directory given, or the preset's, generated into `cache_dir` (or a temporary
/// directory without a cache) on first use.
LoadedDataset load_or_generate(const DatasetOptions& options, const std::string& cache_dir);

/// evaluate() with a progress bar on a terminal and, either way, a summary line on stderr at the
/// end: pairs searched, from the cache, wall time (none for a merge that lacks pairs).
Evaluation evaluate_with_progress(const LoadedDataset& data, EvaluationSettings settings,
                                  const std::string& label);

}  // namespace lmk::cli
