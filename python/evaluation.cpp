// SPDX-License-Identifier: BSD-3-Clause
// lmk.eval and lmk.ablate: evaluations of a dataset directory or a built-in preset, with the CLI's
// cache, its datasets and its JSON (docs/python.md, "Evaluation").
#include "lmk/eval/evaluation.h"

#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <atomic>

#include "bindings.h"
#include "lmk/datasets/benchmark_dataset.h"
#include "lmk/eval/ablation.h"
#include "lmk/eval/evaluation_rows.h"
#include "lmk/eval/internal/ablation_json.h"
#include "lmk/eval/internal/evaluation_document_json.h"

namespace lmk::python {
namespace {

using Progress = std::function<void(std::size_t, std::size_t)>;

// What lmk.eval and lmk.ablate take alike: the dataset (a directory, or a preset generated on
// first use where `lmk eval --preset` generates it), the evaluation's settings and its progress.
// Ctrl-C starts no further search: those under way finish and are cached, and evaluate() throws
// lmk::Interrupted, which reaches Python as KeyboardInterrupt.
struct Run {
  Run(const std::optional<std::string>& dataset, const std::optional<std::string>& preset,
      std::optional<int> seeds, const std::vector<std::string>& types, bool in_context,
      const std::optional<std::string>& cache, int threads, Progress progress,
      const py::kwargs& keywords)
      : progress(std::move(progress)) {
    if (dataset && preset) throw py::value_error("give a dataset or a preset, not both");
    settings.find = settings_from_keywords(keywords);
    settings.in_context_only = in_context;
    settings.threads = threads;
    settings.cache_dir = cache.value_or(default_cache_dir());
    settings.stop_requested = [this] { return stop.load(); };
    settings.progress = [this](std::size_t done, std::size_t total, std::size_t) {
      const py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) {
        PyErr_Clear();  // evaluate() says how many pairs it kept
        stop = true;
      }
      if (this->progress) this->progress(done, total);
    };
    if (dataset) {
      dir = *dataset;
    } else {
      generate.seeds = seeds;
      generate.types = types;
      preset_name = preset.value_or("paper");
      benchmark_preset(preset_name);  // an unknown name fails before anything else
    }
  }
  Run(const Run&) = delete;

  // Generates the preset's dataset if needed and reads the dataset; without the GIL.
  void load() {
    if (dir.empty()) {
      dir = cached_benchmark_dataset(benchmark_dataset_home(settings.cache_dir), preset_name,
                                     generate);
    }
    data = load_dataset(dir);
  }

  EvaluationSettings settings;
  Progress progress;
  std::atomic<bool> stop{false};
  std::string dir, preset_name;
  GenerateOptions generate;
  Dataset data;
};

// The keyword arguments lmk.eval and lmk.ablate share, before the search settings.
#define LMK_RUN_ARGUMENTS                                                       \
  py::arg("preset") = py::none(), py::arg("seeds") = py::none(),                \
  py::arg("types") = std::vector<std::string>{}, py::arg("in_context") = false, \
  py::arg("cache") = py::none(), py::arg("threads") = 0, py::arg("progress") = nullptr

}  // namespace

void bind_evaluation(py::module_& m) {
  m.def(
      "eval",
      [](const std::optional<std::string>& dataset, const std::optional<std::string>& preset,
         std::optional<int> seeds, const std::vector<std::string>& types, bool in_context,
         const std::optional<std::string>& cache, int threads, const Progress& progress,
         const py::kwargs& kwargs) {
        Run run(dataset, preset, seeds, types, in_context, cache, threads, progress, kwargs);
        nlohmann::json result;
        {
          const py::gil_scoped_release release;
          run.load();
          const Evaluation evaluation = evaluate(run.dir, run.data, run.settings);
          result = detail::evaluation_document_to_json(evaluation, evaluation_rows(evaluation));
        }
        return json_to_python(result);
      },
      py::arg("dataset") = py::none(), py::kw_only(), LMK_RUN_ARGUMENTS,
      "Evaluates a dataset directory, or a built-in preset (default 'paper'; `seeds`, `types` as "
      "`lmk eval --seeds --types`), and returns what `lmk eval --json` writes: the table's 'rows' "
      "and every pair's matches. Search settings are keywords as for lmk.find. The cache is the "
      "CLI's (`cache`, default lmk's default cache; '' for none), so both share results. "
      "`in_context`: search in-context pairs only (--pairs in-context). Ctrl-C starts no further "
      "search; those under way are cached, and KeyboardInterrupt says how many pairs are kept.");
  m.def(
      "ablate",
      [](const std::map<std::string, std::vector<py::object>>& vary,
         const std::optional<std::string>& dataset, const std::optional<std::string>& preset,
         std::optional<int> seeds, const std::vector<std::string>& types, bool in_context,
         const std::optional<std::string>& cache, int threads, const Progress& progress,
         const py::kwargs& kwargs) {
        std::vector<AblationAxis> axes;
        for (const auto& [name, values] : vary) {
          std::string text = setting_key(name) + "=";
          for (std::size_t i = 0; i < values.size(); ++i) {
            text += (i ? "," : "") + setting_text(values[i]);
          }
          try {
            axes.push_back(parse_ablation_axis(text));
          } catch (const Error& e) {
            throw py::value_error(e.what());
          }
        }
        Run run(dataset, preset, seeds, types, in_context, cache, threads, progress, kwargs);
        nlohmann::json result;
        {
          const py::gil_scoped_release release;
          run.load();
          result = detail::ablation_to_json(run_ablation(run.dir, run.data, run.settings, axes),
                                            run.data.name);
        }
        return json_to_python(result);
      },
      py::arg("vary"), py::arg("dataset") = py::none(), py::kw_only(), LMK_RUN_ARGUMENTS,
      "Evaluates every combination of the settings in `vary` ({'metric': ['paper', 'vdb'], "
      "'threshold': [0.004, 0.006]}, named and valued as lmk.find's keywords), as `lmk ablate "
      "--vary`, and returns its ablation.json: each variant's values, settings and rows. Other "
      "arguments as lmk.eval's.");
}

}  // namespace lmk::python
