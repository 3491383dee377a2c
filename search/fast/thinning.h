// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Deterministic thinning of point sets: a fixed share of a set stands for all of it where a
// search needs only as many points as fix a pose or rank a candidate. Internal.

#include <algorithm>
#include <cstddef>
#include <vector>

#include "lmk/geometry/point_cloud.h"

namespace lmk::detail {

/// Every k-th index below n, so that at most `cap` remain (deterministic: two sets of one size
/// keep the same indices).
inline Indices thin_indices(std::size_t n, std::size_t cap) {
  Indices out;
  const std::size_t kept = std::min(n, cap);
  const double step = static_cast<double>(n) / static_cast<double>(std::max<std::size_t>(kept, 1));
  for (std::size_t k = 0; k < kept; ++k) out.push_back(static_cast<Index>(k * step));
  return out;
}

/// The items at thin_indices(items.size(), cap).
template <class T>
std::vector<T> thin(const std::vector<T>& items, std::size_t cap) {
  if (items.size() <= cap) return items;
  std::vector<T> out;
  for (Index i : thin_indices(items.size(), cap)) out.push_back(items[i]);
  return out;
}

}  // namespace lmk::detail
