// SPDX-License-Identifier: BSD-3-Clause
// lmk eval-track DIR: each sequence of a dataset (lmk gen --preset moving, or a real sequence's
// with sequences.json) followed by the tracker and scored against its ground truth, frame by frame
// (eval/track_evaluation.h).
#include <cstdio>
#include <memory>

#include "lmk/eval/track_evaluation.h"
#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/error.h"
#include "tools/cli_common.h"
#include "tools/progress.h"

namespace lmk::cli {
namespace {

struct EvalTrackOptions {
  std::string dir, json;
  std::vector<double> tolerance;  ///< mm degrees
  bool allow_outside_files = false;
  TrackEvaluationOptions evaluation;
};

int run_eval_track(EvalTrackOptions& o) {
  if (!o.tolerance.empty()) {
    o.evaluation.tolerance.translation = o.tolerance[0] / 1e3;
    o.evaluation.tolerance.rotation = o.tolerance[1] * M_PI / 180.0;
  }
  if (o.allow_outside_files) o.evaluation.files = DatasetFiles::anywhere;
  const TrackEvaluation evaluation = [&] {
    ProgressBar bar("eval-track");
    o.evaluation.progress = [&bar](std::size_t done, std::size_t total) {
      bar.update(done, total);
    };
    return evaluate_tracking(o.dir, o.evaluation);
  }();
  std::printf("%s", tracking_report(evaluation).c_str());
  if (!o.json.empty()) write_text_atomically(o.json, tracking_json(evaluation));
  return kOk;
}

}  // namespace

Subcommand add_eval_track(CLI::App& app) {
  auto o = std::make_shared<EvalTrackOptions>();
  CLI::App* sub = app.add_subcommand(
      "eval-track",
      "Follow the landmark of each sequence of a dataset (lmk gen --preset moving) and score "
      "every frame against the ground truth: frames within the tolerance, carries noticed, "
      "re-finds, time per frame");
  sub->add_option("dataset", o->dir, "Dataset directory holding dataset.json and sequences.json")
      ->required()
      ->check(CLI::ExistingDirectory);
  add_track_options(sub, o->evaluation.track);
  sub->add_option("--tolerance", o->tolerance,
                  "MM DEGREES: a tracked pose within these of the truth counts as right "
                  "(default 10 5)")
      ->expected(2)
      ->check(within(0.0, 1000.0));
  sub->add_option("--only", o->evaluation.only, "Only the sequences whose names hold TEXT");
  sub->add_option("--json", o->json, "Write the figures and every frame's state and error to FILE");
  sub->add_flag("--allow-outside-files", o->allow_outside_files,
                "Read scene and landmark files the dataset names outside its directory");
  return {sub, [o] { return run_eval_track(*o); }};
}

}  // namespace lmk::cli
