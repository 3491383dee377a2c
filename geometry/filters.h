// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Point filters that return new clouds and leave their input untouched. Every filter keeps the
// attributes of the points it keeps and the sensor pose; its output is unorganised.

#include <cstdint>

#include "lmk/geometry/box.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk {

/// Indices of the points whose coordinates are all finite, in order.
Indices finite_indices(const PointCloud& cloud);
/// The finite points (NaN and Inf removed).
PointCloud remove_non_finite(const PointCloud& cloud);

/// Indices of the finite points inside the oriented box (closed), in order.
Indices indices_in_box(const PointCloud& cloud, const Box& box);
/// The finite points inside the oriented box.
PointCloud crop(const PointCloud& cloud, const Box& box);

/// `count` distinct indices drawn uniformly from [0, n) with a seeded generator, in increasing
/// order. The same (n, count, seed) gives the same indices on every platform. count >= n returns
/// all of [0, n).
Indices random_sample_indices(std::size_t n, std::size_t count, std::uint64_t seed);
/// `count` finite points drawn uniformly without replacement (seeded, order preserved).
PointCloud random_sample(const PointCloud& cloud, std::size_t count, std::uint64_t seed);

}  // namespace lmk
