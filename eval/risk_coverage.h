// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What a confidence is worth (issue #45; docs/evaluation.md, "Confidence"): the risk-coverage
// curve of the best matches (as the confidence cut falls, the share of in-context pairs answered
// against the precision of those answers) and the reliability of the probabilities (predicted
// against observed, and the expected calibration error).

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lmk/eval/evaluation.h"
#include "lmk/eval/text_table.h"

namespace lmk {

/// One point of the curve: every best match with a confidence of at least `cut` answered.
struct RiskCoveragePoint {
  double cut = 0.0;
  std::size_t answered = 0;  ///< pairs whose best match passes the cut
  std::size_t correct = 0;   ///< of those, best matches within tolerance of an instance
  double coverage = 0.0;     ///< answered / pairs
  double precision = 0.0;    ///< correct / answered
};

struct RiskCoverage {
  /// In-context pairs counted: those whose best match (below the threshold) does not lie on an
  /// ignored instance (evaluation.h, kIgnoredHiddenFraction), answered or not.
  std::size_t pairs = 0;
  std::vector<RiskCoveragePoint> curve;  ///< one point per distinct confidence, the cut falling
  /// The area under the risk (1 - precision) against coverage, from no answer to every best match:
  /// the mean risk a user meets as the cut falls, lower is better (0: every answer right).
  double area = 0.0;
  /// The most pairs answered at a precision of at least 0.95 and 0.98 (nothing when none is), and
  /// the cut that answers them.
  std::optional<RiskCoveragePoint> at_95, at_98;
};

/// The curve of `evaluation`'s in-context best matches (assumption 3) below its threshold, whatever
/// its min_confidence (the curve is every cut). Pairs are taken from `select` when given (a range
/// bin), else all.
RiskCoverage risk_coverage(const Evaluation& evaluation,
                           const std::function<bool(const PairResult&)>& select = {});

/// The point of `curve` at a cut: the pairs whose best match has a confidence of at least `cut`
/// (nothing answered when none has).
RiskCoveragePoint risk_coverage_at(const RiskCoverage& curve, double cut);

/// A selection of the pairs whose first instance not ignored lies at a range in [low, high) m
/// from the scene's sensor (the answered share within 2 m, at 2-3 m).
std::function<bool(const PairResult&)> instance_range_within(double low, double high);

/// A selection of the pairs whose landmark's capture box has a diagonal in [low, high) m.
std::function<bool(const PairResult&)> landmark_size_within(double low, double high);

struct ReliabilityBin {
  double low = 0.0, high = 0.0;  ///< the predicted probabilities it holds, [low, high)
  std::size_t matches = 0;
  double predicted = 0.0;  ///< mean predicted probability
  double observed = 0.0;   ///< share within tolerance of an instance
};

struct Reliability {
  std::vector<ReliabilityBin> bins;  ///< 10 bins of predicted probability, empty ones included
  std::size_t matches = 0;
  std::size_t right = 0;  ///< of those, the ones within tolerance of an instance
  /// Expected calibration error: the matches' share of each bin times its |predicted - observed|.
  double ece = 0.0;
};

/// Calls `visit(found, right, best)` for every match below the evaluation's threshold in its
/// in-context pairs, best first within each pair (`best`: the pair's best below the threshold),
/// right when the protocol assigns it to an instance (assign_matches), those on instances the
/// protocol ignores left out: the matches reliability() and the calibration's fit count.
void for_each_counted_match(
    const Evaluation& evaluation,
    const std::function<void(const FoundBox& found, bool right, bool best)>& visit);

/// The reliability of every match for_each_counted_match() visits: what the probability claims to
/// predict. Matches without a probability are left out.
Reliability reliability(const Evaluation& evaluation, int bins = 10);

/// The cuts `lmk eval` reports the curve at, beside the evaluation's own min_confidence.
inline const std::vector<double>& reported_confidence_cuts() {
  static const std::vector<double> cuts = {0.5, 0.8, 0.9, 0.95};
  return cuts;
}

/// The risk-coverage table: one row per reported cut (and the evaluation's own), and the rows for
/// precision 0.95 and 0.98; with `ranges`, one more per 1 m range bin from 0 to 3 m and beyond,
/// and per landmark size (the capture box's diagonal: under 10 cm, 10-20, 20-40, 40 cm and more),
/// at the evaluation's cut (kDefaultMinConfidence when it sets none).
TextTable risk_coverage_table(const Evaluation& evaluation, bool ranges);

/// Two lines: the pairs, the area under the curve and the expected calibration error, and the
/// reliability bins ("0.9-1.0: 0.95 predicted, 0.97 observed, 120 matches"). Says so when the
/// evaluation's metric has no calibration.
std::string confidence_summary(const Evaluation& evaluation);

}  // namespace lmk
