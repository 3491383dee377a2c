// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Summary statistics shared by the benchmark and the evaluation.

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace lmk {

/// The median (the mean of the two middle values for an even count); nothing for no values.
inline std::optional<double> median(std::vector<double> values) {
  if (values.empty()) return std::nullopt;
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  if (values.size() % 2 == 1) return values[mid];
  const double upper = values[mid];
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + mid));
}

/// The value at rank round(q (n - 1)) of the sorted values (the nearest rank, no interpolation: a
/// time that was measured), for q in [0, 1]; 0 for no values. What lmk track and lmk eval-track
/// report as the median and 95th percentile time per frame.
inline double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(std::round(q * static_cast<double>(values.size() - 1)))];
}

}  // namespace lmk
