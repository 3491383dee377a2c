// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/filters.h"

#include <algorithm>
#include <numeric>
#include <unordered_map>

#include "lmk/geometry/error.h"
#include "lmk/geometry/random.h"

namespace lmk {

Indices finite_indices(const PointCloud& cloud) {
  Indices out;
  out.reserve(cloud.size());
  for (Index i = 0; i < cloud.size(); ++i) {
    if (is_finite(cloud.points[i])) out.push_back(i);
  }
  return out;
}

PointCloud remove_non_finite(const PointCloud& cloud) {
  return cloud.select(finite_indices(cloud));
}

Indices indices_in_box(const PointCloud& cloud, const Box& box) {
  if (!box.is_valid()) throw Error("crop: the box needs a finite pose and positive finite sides");
  Indices out;
  for (Index i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f& p = cloud.points[i];
    if (is_finite(p) && box.contains(p)) out.push_back(i);
  }
  return out;
}

PointCloud crop(const PointCloud& cloud, const Box& box) {
  return cloud.select(indices_in_box(cloud, box));
}

Indices random_sample_indices(std::size_t n, std::size_t count, std::uint64_t seed) {
  Indices out;
  if (count >= n) {
    out.resize(n);
    std::iota(out.begin(), out.end(), Index{0});
    return out;
  }
  // Partial Fisher-Yates over a virtual identity permutation of [0, n): only the displaced
  // entries are stored, so the cost is O(count) whatever n is. Lookups only, so the hash map's
  // iteration order never matters and the result is deterministic.
  SplitMix64 rng(seed);
  std::unordered_map<std::size_t, std::size_t> displaced;
  const auto value_at = [&](std::size_t pos) {
    const auto it = displaced.find(pos);
    return it == displaced.end() ? pos : it->second;
  };
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t j = i + rng.uniform_index(n - i);
    const std::size_t chosen = value_at(j);
    displaced[j] = value_at(i);
    out.push_back(static_cast<Index>(chosen));
  }
  std::sort(out.begin(), out.end());
  return out;
}

PointCloud random_sample(const PointCloud& cloud, std::size_t count, std::uint64_t seed) {
  const Indices finite = finite_indices(cloud);
  Indices chosen;
  for (Index k : random_sample_indices(finite.size(), count, seed)) chosen.push_back(finite[k]);
  return cloud.select(chosen);
}

}  // namespace lmk
