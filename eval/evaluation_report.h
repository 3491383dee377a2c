// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// An evaluation's report directory: report.json (everything), report.md (the tables) and a
// self-contained report.html with SVG plots: precision and recall against the error threshold per
// setting, the distribution of search times, a per-scene table of the matches and, given the
// dataset, a picture of each failure.

#include <optional>
#include <string>
#include <vector>

#include "lmk/eval/evaluation.h"
#include "lmk/eval/explain.h"

namespace lmk {

struct ThresholdPoint {
  double threshold = 0.0;  ///< m
  std::optional<double> precision, recall;
};

/// Precision and recall of `setting`'s pairs ("all": every pair) under `assumption`, at `steps`
/// thresholds from a tenth of the evaluation's threshold to twice it (errors the evaluation
/// always keeps). Each point applies that threshold to the same search results.
std::vector<ThresholdPoint> threshold_curve(const Evaluation& evaluation,
                                            const std::string& setting, int assumption,
                                            int steps = 20);

/// Writes DIR/report.json, DIR/report.md and DIR/report.html (creating DIR), each atomically.
/// With the evaluated dataset's directory, the report also pictures its failures
/// (eval/failure_pictures.h): each pair with a missed instance or a false match, drawn on its
/// scene's depth image. With `explained` (lmk eval --explain), the report gives the cause of every
/// miss and false match, per setting and per range, and lists each case.
void write_evaluation_report(const std::string& dir, const Evaluation& evaluation,
                             const std::string& dataset_dir = "",
                             const std::vector<ExplainedCase>* explained = nullptr);

}  // namespace lmk
