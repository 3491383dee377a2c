// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Non-max suppression of FindLandmark (Algorithm 1, line 9): "remove all candidates that do not
// have the lowest error within a certain radius".

#include <Eigen/Core>
#include <vector>

#include "lmk/geometry/box.h"

namespace lmk {

/// Indices of the candidates that have the lowest error among all candidates whose centre lies
/// within `radius` of theirs, sorted by increasing error. Taken literally, as the paper states it:
/// a candidate is removed by any better neighbour, even one that is itself removed. Equal errors
/// are broken by the lower index, so the result is deterministic.
std::vector<std::size_t> non_max_suppression(const std::vector<Eigen::Vector3d>& centres,
                                             const std::vector<double>& errors, double radius);

/// The same over matches, or anything with a `box` and an `error`.
template <typename Match>
std::vector<std::size_t> non_max_suppression_of(const std::vector<Match>& matches, double radius) {
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> errors;
  for (const Match& m : matches) {
    centres.push_back(m.box.center());
    errors.push_back(m.error);
  }
  return non_max_suppression(centres, errors, radius);
}

/// Of matches given best first, those whose box centre lies in the box of no better match kept
/// before it: two instances of a landmark cannot fill one space, so a match inside a better one's
/// box is the same object found again, not a second instance. A match dropped this way drops no
/// other (as non_max_suppression keeps only the best within its radius, this keeps the first of
/// each overlapping run). Indices into `boxes`, in order.
std::vector<std::size_t> exclusive_boxes(const std::vector<Box>& boxes);

}  // namespace lmk
