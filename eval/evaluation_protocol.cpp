// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/evaluation_protocol.h"

#include <algorithm>
#include <cmath>

#include "lmk/geometry/pose.h"

namespace lmk {

double rotation_error(const Eigen::Matrix3d& R_truth, const Eigen::Matrix3d& R_found,
                      const Symmetry& symmetry) {
  // The truth turned by its symmetry to face the found pose as nearly as it can; what remains is
  // the error (for an axis of revolution, the swing angle acos(a . R_rel a)).
  return rotation_angle_between(nearest_symmetric_rotation(R_truth, R_found, symmetry), R_found);
}

double translation_error(const Eigen::Isometry3d& truth, const Eigen::Isometry3d& found,
                         const Symmetry& symmetry) {
  return (truth * symmetry.centre - found * symmetry.centre).norm();
}

void Counts::add(const Counts& other) {
  tp += other.tp;
  fp += other.fp;
  fn += other.fn;
  translation_errors.insert(translation_errors.end(), other.translation_errors.begin(),
                            other.translation_errors.end());
  rotation_errors.insert(rotation_errors.end(), other.rotation_errors.begin(),
                         other.rotation_errors.end());
}

std::optional<double> Counts::precision() const {
  if (tp + fp == 0) return std::nullopt;
  return static_cast<double>(tp) / static_cast<double>(tp + fp);
}

std::optional<double> Counts::recall() const {
  if (tp + fn == 0) return std::nullopt;
  return static_cast<double>(tp) / static_cast<double>(tp + fn);
}

namespace {

// The nearest unmatched ground-truth instance within both tolerances, if any.
std::optional<std::size_t> match(const PairInput& pair, const Eigen::Isometry3d& found,
                                 const std::vector<char>& taken, const MatchTolerance& tolerance) {
  std::optional<std::size_t> best;
  double best_distance = 0.0;
  for (std::size_t i = 0; i < pair.truth.size(); ++i) {
    if (taken[i]) continue;
    const double d = translation_error(pair.truth[i], found, pair.symmetry);
    if (d > tolerance.translation) continue;
    if (rotation_error(pair.truth[i].linear(), found.linear(), pair.symmetry) >
        tolerance.rotation) {
      continue;
    }
    if (!best || d < best_distance) best = i, best_distance = d;
  }
  return best;
}

void record_tp(Counts& c, const Eigen::Isometry3d& truth, const Eigen::Isometry3d& found,
               const Symmetry& symmetry) {
  ++c.tp;
  c.translation_errors.push_back(translation_error(truth, found, symmetry));
  c.rotation_errors.push_back(rotation_error(truth.linear(), found.linear(), symmetry));
}

}  // namespace

std::vector<std::optional<std::size_t>> assign_matches(const PairInput& pair,
                                                       const MatchTolerance& tolerance) {
  std::vector<std::optional<std::size_t>> assigned;
  std::vector<char> taken(pair.truth.size(), 0);
  for (const Eigen::Isometry3d& found : pair.found) {
    assigned.push_back(match(pair, found, taken, tolerance));
    if (assigned.back()) taken[*assigned.back()] = 1;
  }
  return assigned;
}

Counts count_all_matches(const PairInput& pair, const MatchTolerance& tolerance) {
  Counts c;
  const auto assigned = assign_matches(pair, tolerance);
  std::vector<char> matched(pair.truth.size(), 0);
  for (std::size_t k = 0; k < assigned.size(); ++k) {
    if (!assigned[k]) {
      ++c.fp;
    } else if (!pair.is_ignored(*assigned[k])) {
      matched[*assigned[k]] = 1;
      record_tp(c, pair.truth[*assigned[k]], pair.found[k], pair.symmetry);
    }
  }
  for (std::size_t t = 0; t < pair.truth.size(); ++t) c.fn += !matched[t] && !pair.is_ignored(t);
  return c;
}

std::vector<Counts> count_all_matches_by(const PairInput& pair, const std::vector<int>& truth_bin,
                                         const std::vector<int>& found_bin, int bins,
                                         const MatchTolerance& tolerance) {
  std::vector<Counts> out(static_cast<std::size_t>(std::max(bins, 0)));
  const auto in = [&](int bin) { return bin >= 0 && bin < bins; };
  const auto assigned = assign_matches(pair, tolerance);
  std::vector<char> matched(pair.truth.size(), 0);
  for (std::size_t k = 0; k < assigned.size(); ++k) {
    if (!assigned[k]) {
      if (in(found_bin[k])) ++out[found_bin[k]].fp;
    } else if (!pair.is_ignored(*assigned[k])) {
      matched[*assigned[k]] = 1;
      const int bin = truth_bin[*assigned[k]];
      if (in(bin)) record_tp(out[bin], pair.truth[*assigned[k]], pair.found[k], pair.symmetry);
    }
  }
  for (std::size_t t = 0; t < pair.truth.size(); ++t) {
    if (!matched[t] && !pair.is_ignored(t) && in(truth_bin[t])) ++out[truth_bin[t]].fn;
  }
  return out;
}

Counts count_best_match(const PairInput& pair, const MatchTolerance& tolerance) {
  Counts c;
  bool any_to_find = false;
  for (std::size_t t = 0; t < pair.truth.size(); ++t) any_to_find |= !pair.is_ignored(t);
  if (pair.found.empty()) {
    c.fn = any_to_find ? 1 : 0;
    return c;
  }
  const std::vector<char> none_taken(pair.truth.size(), 0);
  if (const auto i = match(pair, pair.found.front(), none_taken, tolerance)) {
    if (!pair.is_ignored(*i)) record_tp(c, pair.truth[*i], pair.found.front(), pair.symmetry);
  } else {
    c.fp = 1;
  }
  return c;
}

std::array<Counts, 3> count_assumptions(const std::vector<PairInput>& pairs,
                                        const MatchTolerance& tolerance) {
  std::array<Counts, 3> out;
  for (const PairInput& pair : pairs) {
    const Counts all = count_all_matches(pair, tolerance);
    out[0].add(all);
    if (!pair.in_context) continue;
    out[1].add(all);
    out[2].add(count_best_match(pair, tolerance));
  }
  return out;
}

}  // namespace lmk
