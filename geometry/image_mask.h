// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Binary image masks (row-major, width x height, 1 set, 0 clear).

#include <cstdint>
#include <vector>

namespace lmk {

/// The morphological opening of `mask` by a square of side 2 `radius` + 1: the pixels covered by
/// some such square that lies wholly in the mask. Regions at least that wide keep their whole
/// extent; strips and specks narrower vanish. Beyond the image's edge counts as set, so a region
/// the edge cuts keeps its pixels along it. Linear time (summed-area tables). Throws lmk::Error
/// when the mask is not width x height or the radius is negative.
std::vector<std::uint8_t> open_mask(const std::vector<std::uint8_t>& mask, int width, int height,
                                    int radius);

/// For every pixel, a lower bound of its distance to the nearest set pixel of `mask`, pixels (0 on
/// the mask; +infinity everywhere when nothing is set): the 8-neighbour chamfer distance (steps of
/// 1 and sqrt 2, two passes), which exceeds the Euclidean one by at most 8.24%, divided by that.
std::vector<float> distance_to_mask(const std::vector<std::uint8_t>& mask, int width, int height);

}  // namespace lmk
