// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The rows of the paper's precision/recall table from an evaluation's pairs (evaluation.h): per
// scene setting and assumption, and split by range, by hidden fraction, or by the landmark's views.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "lmk/eval/evaluation.h"
#include "lmk/eval/evaluation_protocol.h"

namespace lmk {

/// One row of the paper's table.
struct EvaluationRow {
  std::string setting;  ///< a scene setting, or "all"
  int assumption = 1;   ///< 1: all pairs, 2: in-context pairs, 3: in context, best match only
  Counts counts;
  std::optional<double> median_translation_error;  ///< m, over true positives
  std::optional<double> median_rotation_error;     ///< rad, over true positives
  std::optional<double> median_seconds;            ///< per search, over the row's pairs
  std::size_t pairs = 0;
};

/// The settings of the evaluation's pairs in order of first appearance, then "all".
std::vector<std::string> evaluation_settings(const Evaluation& evaluation);

/// One row: the pairs of `setting` ("all": every pair) under `assumption`, matches below
/// `threshold`.
EvaluationRow evaluation_row(const Evaluation& evaluation, const std::string& setting,
                             int assumption, double threshold);

/// The table at `threshold` (default: the evaluation's own): each setting of the dataset in order
/// of first appearance, then "all"; per setting assumptions 1 (unless only in-context pairs were
/// searched), 2 and 3.
std::vector<EvaluationRow> evaluation_rows(const Evaluation& evaluation,
                                           std::optional<double> threshold = {});

/// Assumptions 1 (when every pair was searched) and 2, split by range: the distance from the
/// scene's sensor to each ground-truth instance (true positives, false negatives) or to each match
/// (false positives), in bins of `bin_width` m; and assumption 3, each in-context pair's best
/// match in the bin of its first instance not ignored (TP out of `pairs`: how often the best match
/// was right at that range). Rows by bin that holds anything, nearest first, its `setting` naming
/// the bin ("1.0-1.5 m"); median errors as the table's, no times.
std::vector<EvaluationRow> evaluation_rows_by_range(const Evaluation& evaluation,
                                                    std::optional<double> threshold = {},
                                                    double bin_width = 0.5);

/// The bin of a range (m) and its label ("1.0-1.5 m"); of a hidden fraction (the last bin holds
/// 1) and its label ("20-40% hidden"). Shared by the tables and by `--explain`'s.
int range_bin(double range, double bin_width);
std::string range_bin_label(int bin, double bin_width);
int hidden_bin(double hidden, double bin_width);
std::string hidden_bin_label(int bin, double bin_width);

/// Whether the evaluated dataset records the hidden fraction of its instances (pairs[].hidden).
bool records_hidden_fractions(const Evaluation& evaluation);

/// Assumptions 1 (when every pair was searched) and 2, split by the hidden fraction of each
/// ground-truth instance, in bins of `bin_width` ("20-40% hidden"): recall by how much of the
/// landmark its sensor could not see. False matches hide nothing and count in no bin, so the
/// precision of a bin is that of the matches on its instances; assumption 3 as by range. Throws
/// lmk::Error when the dataset records no hidden fraction.
std::vector<EvaluationRow> evaluation_rows_by_hidden(const Evaluation& evaluation,
                                                     std::optional<double> threshold = {},
                                                     double bin_width = 0.2);

/// Assumptions 1 (when every pair was searched), 2 and 3 as by range, split by the landmark's
/// number of views and the azimuth from each instance (or false match) to the nearest of them: the
/// angle, about the landmark's up axis, between the directions from the box's centre to the scene's
/// sensor and to that view's sensor, in bins of `bin_degrees` ("3 views, 15-30 deg"); first the
/// rows of each number of views over every azimuth ("3 views").
std::vector<EvaluationRow> evaluation_rows_by_views(const Evaluation& evaluation,
                                                    std::optional<double> threshold = {},
                                                    double bin_degrees = 15.0);

/// The azimuth (rad, 0 to pi) from a box at `box_pose` (scene frame) of `pair`'s landmark to the
/// nearest of its views, seen from the pair's scene sensor (evaluation_rows_by_views).
double azimuth_to_nearest_view(const PairResult& pair, const Eigen::Isometry3d& box_pose);

}  // namespace lmk
