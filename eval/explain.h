// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `lmk eval --explain`: one cause for every missed instance and every false match of an
// evaluation (docs/evaluation.md, "Why a search missed"), so that a researcher sees whether the
// metric or the search limits recall. Each pair that failed is searched again, keeping every
// candidate (those selection turned down and those non-max suppression removed), and the metric is
// measured at the true pose, aligned and polished from the truth as a candidate there would be.
//
// A missed instance's cause, from the candidates within the protocol's tolerance of it:
//   no candidate        none came near the truth: the search (seeds, voting, alignment) limits
//   suppressed          the near ones were removed by non-max suppression or lay inside a
//                       better-scoring wrong match's box: the score ranks a wrong pose first
//   over threshold      the best near one scored above the threshold
//   coverage            it failed the coverage test
//   empty space         it failed the empty-space test
//   too little shown    a landmark of several views whose visible part could not fix the pose
//   colour differs      the shape matched; the colour term put it over the threshold
// A false match's cause:
//   displaced truth     it suppressed a true candidate of the same pair (within the suppression
//                       radius of the truth, or holding the truth's centre in its box)
//   off pose            it lies on an instance, within twice the tolerance, but beyond it
//   look-alike          elsewhere: a look-alike that passed every test

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lmk/datasets/dataset.h"
#include "lmk/eval/evaluation.h"
#include "lmk/eval/text_table.h"
#include "lmk/search/find_landmark.h"

namespace lmk {

/// Why an instance was missed (the first seven) or a false match reported (the last three).
enum class ExplainCause {
  no_candidate,
  suppressed,
  over_threshold,
  coverage,
  empty_space,
  too_little_shown,  ///< a landmark of several views whose visible part could not fix the pose
  colour_differs,    ///< the shape matched; the colour term put it over the threshold
  displaced_truth,
  off_pose,
  look_alike,
};
/// What tables and JSON say: "no candidate", "suppressed", "over threshold", "coverage", "empty
/// space", "too little shown", "colour differs", "displaced truth", "off pose", "look-alike".
const char* to_string(ExplainCause cause);

/// The causes, in the order tables list them.
const std::vector<ExplainCause>& miss_causes();
const std::vector<ExplainCause>& false_match_causes();

/// What became of a candidate near a missed instance: accepted (no reason), or the reason
/// selection or non-max suppression gave, with its error.
struct CandidateFate {
  double error = 0.0;
  std::optional<RejectionReason> rejected;
};

/// The cause of a miss from the candidates within tolerance of the truth, best (lowest error)
/// first, at `threshold`: the best one that reached selection decides (non-max suppression keeps
/// the best of neighbours, so one it removed lost to a better one); none near is "no candidate",
/// and near ones all removed by suppression, or accepted below the threshold yet not reported,
/// lost to a wrong one.
ExplainCause miss_cause(const std::vector<CandidateFate>& near, double threshold);

struct ExplainedCase {
  std::string scene, landmark, setting;
  bool missed = true;  ///< a missed instance; false: a false match
  ExplainCause cause = ExplainCause::no_candidate;
  Box box;             ///< the instance's box (missed) or the match's (false match), scene frame
  double range = 0.0;  ///< from the scene's sensor to the box centre, m
  /// A missed instance: the fraction of it the scene's sensor could not see, when the dataset
  /// records it (pairs[].hidden): a partial view at the image's edge or behind an occluder.
  std::optional<double> hidden;
  /// The metric at the pair's true pose (for a false match, at its pair's first instance, if
  /// any), aligned and polished from the truth (score_pose).
  std::optional<double> truth_error;
  /// A missed instance: the best wrong match of its pair that was reported; a false match: its own.
  std::optional<double> winner_error;
  /// The calibrated confidence of that wrong match (match_confidence.h), when it has one: how sure
  /// the search was of the pose it got wrong.
  std::optional<double> winner_confidence;
  /// A missed instance: the nearest candidate of any fate, m and rad (modulo symmetry).
  std::optional<double> nearest_candidate_translation, nearest_candidate_rotation;
  /// A missed instance: how far aligning and polishing moved the true pose, m and rad (modulo
  /// symmetry): the pose a search that started at the truth would report. Beyond the tolerance,
  /// the metric's own optimum misses the truth, and no search could find it (or the truth is off).
  std::optional<double> truth_drift_translation, truth_drift_rotation;
};

/// The causes of every miss and false match of `evaluation` (assumption 2 when it searched the
/// in-context pairs only, else 1), searching the pairs that failed again in `dataset_dir`.
/// `progress` gets (pairs done, pairs to explain).
std::vector<ExplainedCase> explain_evaluation(
    const std::string& dataset_dir, const Dataset& dataset, const Evaluation& evaluation,
    const std::function<void(std::size_t, std::size_t)>& progress = {});

/// A count of each cause per group: rows by setting ("all" last), or by range in bins of
/// `bin_width` m when it is given; cause_rows_by_hidden, the misses by their hidden fraction in
/// bins of `bin_width` ("20-40% hidden"), false matches only in "all" (they hide nothing).
struct CauseRow {
  std::string group;
  std::vector<std::size_t> missed;                                ///< by miss_causes()
  std::vector<std::size_t> false_matches;                         ///< by false_match_causes()
  std::optional<double> median_truth_error, median_winner_error;  ///< over the group's misses
  /// Over the group's misses and false matches: the median confidence of the wrong matches.
  std::optional<double> median_winner_confidence;
};
std::vector<CauseRow> cause_rows(const std::vector<ExplainedCase>& cases,
                                 std::optional<double> bin_width = std::nullopt);
std::vector<CauseRow> cause_rows_by_hidden(const std::vector<ExplainedCase>& cases,
                                           double bin_width = 0.2);

/// The rows as a table: a column per cause, then the median metric value at the true poses of the
/// misses beside the median of the wrong matches that were reported, in `metric`'s unit, and the
/// median confidence of the wrong matches.
TextTable cause_table(const std::vector<CauseRow>& rows, const std::string& metric);

}  // namespace lmk
