// SPDX-License-Identifier: BSD-3-Clause
// lmk calibrate-confidence DATASET... -o FILE [--check DATASET...] [--features NAME...]
//                          [--ridge R] [--note TEXT] [search options] [--cache DIR | --no-cache]
// Fits the confidence calibration (search/confidence/confidence_calibration.h) on the in-context
// pairs of labelled datasets (eval/confidence_fit.h), reports how it does on them and on --check
// datasets it is not fitted on, and writes the file `--calibration` (or `--confidence-calibration`)
// reads. Each DATASET is a directory, or a preset's name generated once into the cache.

#include <cstdio>
#include <filesystem>
#include <memory>

#include "lmk/datasets/benchmark_dataset.h"
#include "lmk/eval/confidence_fit.h"
#include "lmk/eval/risk_coverage.h"
#include "lmk/eval/text_table.h"
#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/error.h"
#include "tools/cli_common.h"
#include "tools/eval_common.h"

namespace lmk::cli {
namespace {

struct CalibrateConfidenceOptions {
  std::vector<std::string> fit, check, features;
  std::string output, note;
  double ridge = ConfidenceFitSettings().ridge;
  EvaluationSettings settings;
};

// A dataset argument: a directory, else a preset's name.
DatasetOptions dataset_named(const std::string& name) {
  DatasetOptions d;
  if (std::filesystem::is_directory(name)) {
    d.dir = name;
  } else {
    benchmark_preset(name);  // neither: "unknown preset" names the known ones
    d.preset = name;
  }
  return d;
}

struct Evaluated {
  std::string name;
  bool fitted = false;
  Evaluation evaluation;
};

// One row: the matches, how many are right, the calibration error, and the best matches answered
// (with their precision) at each reported cut and at precision 0.95.
std::vector<std::string> row(const Evaluated& e) {
  const Reliability r = reliability(e.evaluation);
  const RiskCoverage curve = risk_coverage(e.evaluation);
  std::vector<std::string> out = {e.name, e.fitted ? "fit" : "check", std::to_string(r.matches),
                                  std::to_string(r.right), format_optional(r.ece, 3)};
  const auto answered = [&](const std::optional<RiskCoveragePoint>& p) {
    if (!p || p->answered == 0) return std::string("0 of ") + std::to_string(curve.pairs);
    return std::to_string(p->answered) + " of " + std::to_string(curve.pairs) + " at " +
           format_optional(p->precision, 3);
  };
  for (const double cut : reported_confidence_cuts())
    out.push_back(answered(risk_coverage_at(curve, cut)));
  out.push_back(answered(curve.at_95));
  return out;
}

int run_calibrate_confidence(CalibrateConfidenceOptions& o) {
  o.settings.in_context_only = true;  // the pairs whose truth a real dataset labels
  std::vector<Evaluated> evaluated;
  std::string metric;
  const auto add = [&](const std::string& name, bool fitted) {
    const LoadedDataset data = load_or_generate(dataset_named(name), o.settings.cache_dir);
    Evaluated e{name, fitted, evaluate_with_progress(data, o.settings, name)};
    const std::string& m = e.evaluation.settings.find.selection.metric;
    if (!metric.empty() && m != metric)
      throw Error("calibrate-confidence: " + name + " was searched with metric " + m +
                  ", the others with " + metric);
    metric = m;
    evaluated.push_back(std::move(e));
  };
  for (const std::string& name : o.fit) add(name, true);
  for (const std::string& name : o.check) add(name, false);

  std::vector<ConfidenceSample> samples;
  std::string fitted_on;
  for (const Evaluated& e : evaluated) {
    if (!e.fitted) continue;
    const std::vector<ConfidenceSample> s = confidence_samples(e.evaluation);
    samples.insert(samples.end(), s.begin(), s.end());
    fitted_on += (fitted_on.empty() ? "" : ", ") + e.name;
  }
  ConfidenceFitSettings fit;
  fit.features = o.features;
  fit.ridge = o.ridge;
  const std::string note = (o.note.empty() ? "" : o.note + "; ") + "lmk calibrate-confidence on " +
                           fitted_on + ", search revision " + std::to_string(kSearchRevision) +
                           ", metric " + metric + ", " + std::to_string(samples.size()) +
                           " matches";
  const ConfidenceCalibration calibration = fit_confidence_calibration(samples, fit, metric, note);
  write_text_atomically(o.output, confidence_calibration_json(calibration));

  std::printf("weights: bias %.4f", calibration.bias);
  for (const auto& [name, w] : calibration.weights) std::printf(", %s %.4f", name.c_str(), w);
  std::printf("\n\n");
  TextTable table;
  table.header = {"dataset", "role", "matches", "right", "ECE"};
  for (const double cut : reported_confidence_cuts())
    table.header.push_back("best >= " + format_optional(cut, 2));
  table.header.push_back("most at precision 0.95");
  table.numeric = {false, false, true, true, true, true, true, true, true, true};
  for (Evaluated& e : evaluated) {
    recalibrate(e.evaluation, calibration);
    table.rows.push_back(row(e));
  }
  std::printf("%s\nwrote %s\n", table.plain().c_str(), o.output.c_str());
  return kOk;
}

}  // namespace

Subcommand add_calibrate_confidence(CLI::App& app) {
  auto o = std::make_shared<CalibrateConfidenceOptions>();
  CLI::App* sub = app.add_subcommand(
      "calibrate-confidence",
      "Fit the confidence calibration on labelled datasets (their in-context pairs), for "
      "--confidence-calibration: a team's own robot, sensor and landmarks");
  sub->add_option("datasets", o->fit,
                  "Datasets to fit on: directories (lmk gen), or presets' names generated once "
                  "into the cache")
      ->required();
  sub->add_option("--check", o->check,
                  "Datasets to report on, not fit on (tune on one real sequence, report on "
                  "another)");
  sub->add_option("--features", o->features,
                  "The features to weigh (default: every one; docs/evaluation.md, \"A confidence "
                  "that transfers\")");
  sub->add_option("--ridge", o->ridge, "Ridge on every weight but the bias")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--note", o->note, "What it was fitted on, for people (kept in the file)");
  sub->add_option("-o,--output", o->output, "The calibration file to write (.json)")
      ->required()
      ->check(output_extension(".json", "a confidence calibration"));
  add_search_options(sub, o->settings.find);
  add_evaluation_options(sub, o->settings);
  return {sub, [o] { return run_calibrate_confidence(*o); }};
}

}  // namespace lmk::cli
