// SPDX-License-Identifier: BSD-3-Clause
// lmk.eval: an evaluation of a dataset directory or a built-in preset, with the CLI's cache, its
// datasets and its JSON (docs/python.md, "Evaluation").
#include "lmk/eval/evaluation.h"

#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <atomic>

#include "bindings.h"
#include "lmk/eval/benchmark_dataset.h"
#include "lmk/eval/detail/evaluation_json.h"

namespace lmk::python {
namespace {

// The dataset's directory: `dataset` as given, or the preset's, generated on first use where
// `lmk eval --preset` generates it (benchmark_dataset_home), so that both find it there.
std::string dataset_dir(const std::optional<std::string>& dataset,
                        const std::optional<std::string>& preset, const GenerateOptions& generate,
                        const std::string& cache_dir) {
  if (dataset && preset) throw py::value_error("eval: give a dataset or a preset, not both");
  if (dataset) return *dataset;
  const std::string name = preset.value_or("paper");
  benchmark_preset(name);  // an unknown name fails before anything else
  return cached_benchmark_dataset(benchmark_dataset_home(cache_dir), name, generate);
}

}  // namespace

void bind_evaluation(py::module_& m) {
  m.def(
      "eval",
      [](const std::optional<std::string>& dataset, const std::optional<std::string>& preset,
         std::optional<int> seeds, const std::vector<std::string>& types, bool in_context,
         const std::optional<std::string>& cache, int threads,
         const std::function<void(std::size_t, std::size_t)>& progress, const py::kwargs& kwargs) {
        EvaluationSettings settings;
        settings.find = settings_from_keywords(kwargs);
        settings.in_context_only = in_context;
        settings.threads = threads;
        settings.cache_dir = cache.value_or(default_cache_dir());
        GenerateOptions generate;
        generate.seeds = seeds;
        generate.types = types;
        // Ctrl-C: the searches under way finish and are cached, and the next run resumes.
        std::atomic<bool> stop{false};
        settings.stop_requested = [&stop] { return stop.load(); };
        settings.progress = [&progress, &stop](std::size_t done, std::size_t total, std::size_t) {
          const py::gil_scoped_acquire acquire;
          if (PyErr_CheckSignals() != 0) {
            PyErr_Clear();
            stop = true;
          }
          if (progress) progress(done, total);
        };
        Evaluation evaluation;
        std::vector<EvaluationRow> rows;
        {
          const py::gil_scoped_release release;
          const std::string dir = dataset_dir(dataset, preset, generate, settings.cache_dir);
          evaluation = evaluate(dir, load_dataset(dir), settings);
          rows = evaluation_rows(evaluation);
        }
        return json_to_python(detail::evaluation_to_json(evaluation, rows));
      },
      py::arg("dataset") = py::none(), py::kw_only(), py::arg("preset") = py::none(),
      py::arg("seeds") = py::none(), py::arg("types") = std::vector<std::string>{},
      py::arg("in_context") = false, py::arg("cache") = py::none(), py::arg("threads") = 0,
      py::arg("progress") = nullptr,
      "Evaluates a dataset directory, or a built-in preset (default 'paper'; `seeds`, `types` as "
      "`lmk eval --seeds --types`), and returns what `lmk eval --json` writes: the table's 'rows' "
      "and every pair's matches. Search settings are keywords as for lmk.find. The cache is the "
      "CLI's (`cache`, default lmk's default cache; '' for none), so both share results. "
      "`in_context`: search in-context pairs only (--pairs in-context). Ctrl-C stops starting "
      "searches; those under way are cached and lmk.Error says how many pairs are kept.");
}

}  // namespace lmk::python
