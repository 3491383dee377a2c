// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/non_max_suppression.h"

#include <algorithm>
#include <numeric>

#include "lmk/geometry/error.h"

namespace lmk {

std::vector<std::size_t> non_max_suppression(const std::vector<Eigen::Vector3d>& centres,
                                             const std::vector<double>& errors, double radius) {
  if (centres.size() != errors.size()) {
    throw Error("non_max_suppression: " + std::to_string(centres.size()) + " centres for " +
                std::to_string(errors.size()) + " errors");
  }
  const auto better = [&](std::size_t a, std::size_t b) {
    return errors[a] < errors[b] || (errors[a] == errors[b] && a < b);
  };
  const double r2 = radius * radius;
  std::vector<std::size_t> kept;
  // At most a thousand candidates per search (the paper's seed cap): the quadratic scan is cheap
  // next to one ICP.
  for (std::size_t i = 0; i < centres.size(); ++i) {
    bool best = true;
    for (std::size_t j = 0; j < centres.size() && best; ++j) {
      if (j != i && (centres[j] - centres[i]).squaredNorm() <= r2 && better(j, i)) best = false;
    }
    if (best) kept.push_back(i);
  }
  std::sort(kept.begin(), kept.end(), better);
  return kept;
}

std::vector<std::size_t> exclusive_boxes(const std::vector<Box>& boxes) {
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    if (std::none_of(kept.begin(), kept.end(),
                     [&](std::size_t k) { return boxes[k].contains(boxes[i].center()); })) {
      kept.push_back(i);
    }
  }
  return kept;
}

}  // namespace lmk
