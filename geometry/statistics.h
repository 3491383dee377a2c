// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Summary statistics shared by the benchmark and the evaluation.

#include <algorithm>
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

}  // namespace lmk
