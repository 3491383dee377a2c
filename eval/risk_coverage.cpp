// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/risk_coverage.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace lmk {
namespace {

struct Answer {
  double confidence;  ///< -infinity without a probability: never answered at a cut above 0
  bool correct;
};

// The found boxes of `pair` below `threshold`, best first, with the protocol's assignment of each
// (assign_matches; an instance for a right one).
struct Assessed {
  std::vector<const FoundBox*> found;
  std::vector<std::optional<std::size_t>> assigned;
  PairInput input;
};

Assessed assess(const PairResult& pair, double threshold, const MatchTolerance& tolerance) {
  Assessed a;
  a.input = matches_within(pair, threshold);
  for (const FoundBox& f : pair.found) {
    if (f.error < threshold) a.found.push_back(&f);
  }
  a.assigned = assign_matches(a.input, tolerance);
  return a;
}

double answer_confidence(const FoundBox& f) {
  const double p = f.confidence.probability;
  return std::isnan(p) ? -std::numeric_limits<double>::infinity() : p;
}

// Each counted pair's best match, or a pair counted with nothing to answer.
std::vector<Answer> best_answers(const Evaluation& e,
                                 const std::function<bool(const PairResult&)>& select,
                                 std::size_t& pairs) {
  const double threshold = *e.settings.find.selection.threshold;
  std::vector<Answer> answers;
  pairs = 0;
  for (const PairResult& p : e.pairs) {
    if (!p.in_context || (select && !select(p))) continue;
    const Assessed a = assess(p, threshold, e.settings.tolerance);
    if (a.found.empty()) {
      ++pairs;  // never answered: a miss at every cut
      continue;
    }
    const std::optional<std::size_t>& on = a.assigned.front();
    if (on && a.input.is_ignored(*on)) continue;  // on an instance the protocol ignores
    ++pairs;
    answers.push_back({answer_confidence(*a.found.front()), on.has_value()});
  }
  std::stable_sort(answers.begin(), answers.end(),
                   [](const Answer& x, const Answer& y) { return x.confidence > y.confidence; });
  return answers;
}

}  // namespace

RiskCoverage risk_coverage(const Evaluation& e,
                           const std::function<bool(const PairResult&)>& select) {
  RiskCoverage out;
  const std::vector<Answer> answers = best_answers(e, select, out.pairs);
  if (out.pairs == 0) return out;
  const double n = static_cast<double>(out.pairs);
  std::size_t answered = 0, correct = 0;
  // Answers of one confidence pass or fail a cut together: one point per distinct confidence.
  for (std::size_t i = 0; i < answers.size();) {
    std::size_t j = i;
    while (j < answers.size() && answers[j].confidence == answers[i].confidence) {
      correct += answers[j].correct ? 1 : 0;
      ++j;
    }
    if (std::isinf(answers[i].confidence)) break;  // no probability: never answered
    answered = j;
    RiskCoveragePoint point{answers[i].confidence, answered, correct,
                            static_cast<double>(answered) / n,
                            static_cast<double>(correct) / static_cast<double>(answered)};
    out.area += static_cast<double>(j - i) * (1.0 - point.precision) / n;
    out.curve.push_back(point);
    i = j;
  }
  for (const RiskCoveragePoint& point : out.curve) {
    if (point.precision >= 0.95 && (!out.at_95 || point.answered > out.at_95->answered))
      out.at_95 = point;
    if (point.precision >= 0.98 && (!out.at_98 || point.answered > out.at_98->answered))
      out.at_98 = point;
  }
  return out;
}

RiskCoveragePoint risk_coverage_at(const RiskCoverage& curve, double cut) {
  // The curve falls in confidence and grows in answers: its last point at or above the cut.
  RiskCoveragePoint point;
  for (const RiskCoveragePoint& p : curve.curve) {
    if (!(p.cut >= cut)) break;
    point = p;
  }
  point.cut = cut;
  return point;
}

std::function<bool(const PairResult&)> landmark_size_within(double low, double high) {
  return
      [low, high](const PairResult& p) { return p.landmark_size >= low && p.landmark_size < high; };
}

std::function<bool(const PairResult&)> instance_range_within(double low, double high) {
  return [low, high](const PairResult& p) {
    for (std::size_t i = 0; i < p.truth.size(); ++i) {
      if (i < p.truth_hidden.size() && p.truth_hidden[i] >= kIgnoredHiddenFraction) continue;
      const double range = (p.truth[i].translation() - p.sensor_position).norm();
      return range >= low && range < high;
    }
    return false;
  };
}

void for_each_counted_match(
    const Evaluation& e, const std::function<void(const FoundBox&, bool right, bool best)>& visit) {
  const double threshold = *e.settings.find.selection.threshold;
  for (const PairResult& p : e.pairs) {
    if (!p.in_context) continue;
    const Assessed a = assess(p, threshold, e.settings.tolerance);
    for (std::size_t i = 0; i < a.found.size(); ++i) {
      const std::optional<std::size_t>& on = a.assigned[i];
      if (on && a.input.is_ignored(*on)) continue;
      visit(*a.found[i], on.has_value(), i == 0);
    }
  }
}

Reliability reliability(const Evaluation& e, int bins) {
  Reliability out;
  std::vector<double> predicted(static_cast<std::size_t>(bins), 0.0);
  std::vector<std::size_t> right(static_cast<std::size_t>(bins), 0);
  out.bins.resize(static_cast<std::size_t>(bins));
  for (int b = 0; b < bins; ++b) {
    out.bins[b].low = static_cast<double>(b) / bins;
    out.bins[b].high = static_cast<double>(b + 1) / bins;
  }
  for_each_counted_match(e, [&](const FoundBox& found, bool is_right, bool) {
    const double probability = found.confidence.probability;
    if (std::isnan(probability)) return;
    const auto b = static_cast<std::size_t>(
        std::clamp(static_cast<int>(std::floor(probability * bins)), 0, bins - 1));
    ++out.bins[b].matches;
    predicted[b] += probability;
    right[b] += is_right ? 1 : 0;
    out.right += is_right ? 1 : 0;
    ++out.matches;
  });
  for (std::size_t b = 0; b < out.bins.size(); ++b) {
    ReliabilityBin& bin = out.bins[b];
    if (bin.matches == 0) continue;
    const double m = static_cast<double>(bin.matches);
    bin.predicted = predicted[b] / m;
    bin.observed = static_cast<double>(right[b]) / m;
    out.ece += m / static_cast<double>(out.matches) * std::abs(bin.predicted - bin.observed);
  }
  return out;
}

}  // namespace lmk

namespace lmk {
namespace {

std::string fixed(double v, int decimals) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.*f", decimals, v);
  return text;
}

std::vector<std::string> point_row(const std::string& label, const RiskCoveragePoint& p,
                                   std::size_t pairs) {
  return {label, fixed(p.cut, 3), std::to_string(p.answered) + " of " + std::to_string(pairs),
          fixed(p.coverage, 3), p.answered ? fixed(p.precision, 3) : "-"};
}

// The cut the range rows are at: the evaluation's own, else the usual robot's.
double range_cut(const Evaluation& e) {
  const double own = e.settings.find.selection.min_confidence;
  return own > 0.0 ? own : kDefaultMinConfidence;
}

}  // namespace

TextTable risk_coverage_table(const Evaluation& e, bool ranges) {
  TextTable t;
  t.header = {"best matches in context", "cut", "answered", "coverage", "precision"};
  t.numeric = {false, true, true, true, true};
  const RiskCoverage curve = risk_coverage(e);
  std::vector<double> cuts = reported_confidence_cuts();
  const double own = e.settings.find.selection.min_confidence;
  if (own > 0.0 && std::find(cuts.begin(), cuts.end(), own) == cuts.end()) cuts.push_back(own);
  std::sort(cuts.begin(), cuts.end());
  for (double cut : cuts) {
    t.rows.push_back(point_row(cut == own ? "at the cut (--min-confidence)" : "at a cut",
                               risk_coverage_at(curve, cut), curve.pairs));
  }
  const auto best = [&](const char* label, const std::optional<RiskCoveragePoint>& p) {
    if (p) {
      t.rows.push_back(point_row(label, *p, curve.pairs));
    } else {
      t.rows.push_back({label, "-", "0 of " + std::to_string(curve.pairs), "0.000", "-"});
    }
  };
  best("most answered at precision 0.95", curve.at_95);
  best("most answered at precision 0.98", curve.at_98);
  if (ranges) {
    const double cut = range_cut(e);
    const double bins[][2] = {{0.0, 1.0}, {1.0, 2.0}, {2.0, 3.0}, {3.0, 1e9}};
    for (const auto& bin : bins) {
      const auto select = instance_range_within(bin[0], bin[1]);
      const RiskCoverage in_bin = risk_coverage(e, select);
      if (in_bin.pairs == 0) continue;
      const std::string label = "instance at " + fixed(bin[0], 0) +
                                (bin[1] > 100.0 ? "+ m" : "-" + fixed(bin[1], 0) + " m");
      t.rows.push_back(point_row(label, risk_coverage_at(in_bin, cut), in_bin.pairs));
    }
    const double sizes[][2] = {{0.0, 0.1}, {0.1, 0.2}, {0.2, 0.4}, {0.4, 1e9}};
    for (const auto& bin : sizes) {
      const RiskCoverage in_bin = risk_coverage(e, landmark_size_within(bin[0], bin[1]));
      if (in_bin.pairs == 0) continue;
      const std::string label = "landmark box diagonal " + fixed(100.0 * bin[0], 0) +
                                (bin[1] > 100.0 ? "+ cm" : "-" + fixed(100.0 * bin[1], 0) + " cm");
      t.rows.push_back(point_row(label, risk_coverage_at(in_bin, cut), in_bin.pairs));
    }
  }
  return t;
}

std::string confidence_summary(const Evaluation& e) {
  const Reliability r = reliability(e);
  if (r.matches == 0) {
    return "confidence: no match has a probability (no calibration for the metric '" +
           e.settings.find.selection.metric + "')\n";
  }
  const RiskCoverage curve = risk_coverage(e);
  std::string out = "confidence: " + std::to_string(curve.pairs) +
                    " in-context pairs, area under the risk-coverage curve " +
                    fixed(curve.area, 3) + "; expected calibration error " + fixed(r.ece, 3) +
                    " over " + std::to_string(r.matches) + " matches\nreliability:";
  for (const ReliabilityBin& b : r.bins) {
    if (b.matches == 0) continue;
    out += " " + fixed(b.low, 1) + "-" + fixed(b.high, 1) + ": " + fixed(b.predicted, 2) + " / " +
           fixed(b.observed, 2) + " (" + std::to_string(b.matches) + ");";
  }
  out.back() = '\n';
  return out;
}

}  // namespace lmk
