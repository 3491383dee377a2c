// SPDX-License-Identifier: BSD-3-Clause
// Binary image masks (geometry/image_mask.h): the opening keeps wide regions whole and drops
// narrow strips; the chamfer distance is a lower bound of the Euclidean one, within its 8.24%.

#include "lmk/geometry/image_mask.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "lmk/geometry/error.h"

namespace lmk {
namespace {

constexpr int kW = 60, kH = 40;

std::vector<std::uint8_t> with_rect(std::vector<std::uint8_t> mask, int x0, int y0, int x1,
                                    int y1) {
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) mask[y * kW + x] = 1;
  return mask;
}

TEST(ImageMask, OpeningKeepsWideRegionsWholeAndDropsNarrowStrips) {
  std::vector<std::uint8_t> mask(kW * kH, 0);
  mask = with_rect(mask, 5, 5, 20, 20);   // 15 x 15: kept
  mask = with_rect(mask, 30, 2, 33, 38);  // a strip 3 wide: dropped
  const std::vector<std::uint8_t> opened = open_mask(mask, kW, kH, 3);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const bool in_square = x >= 5 && x < 20 && y >= 5 && y < 20;
      EXPECT_EQ(opened[y * kW + x] != 0, in_square) << x << ", " << y;
    }
  }
  // Radius 0 is the mask itself.
  EXPECT_EQ(open_mask(mask, kW, kH, 0), mask);
}

TEST(ImageMask, ARegionTheEdgeCutsKeepsItsPixelsAlongTheEdge) {
  // 5 rows along the top edge and wide: a square of radius 3 about row 0 holds rows 0 to 3 only.
  const std::vector<std::uint8_t> mask =
      with_rect(std::vector<std::uint8_t>(kW * kH, 0), 0, 0, kW, 5);
  EXPECT_EQ(open_mask(mask, kW, kH, 3), mask);
}

TEST(ImageMask, ChamferDistanceIsALowerBoundWithinItsExcess) {
  std::mt19937 rng(7);
  std::vector<std::uint8_t> mask(kW * kH, 0);
  std::vector<std::pair<int, int>> set;
  for (int i = 0; i < 6; ++i) {
    const int x = static_cast<int>(rng() % kW), y = static_cast<int>(rng() % kH);
    mask[y * kW + x] = 1;
    set.emplace_back(x, y);
  }
  const std::vector<float> d = distance_to_mask(mask, kW, kH);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      double exact = 1e9;
      for (const auto& [sx, sy] : set) exact = std::min(exact, std::hypot(x - sx, y - sy));
      EXPECT_LE(d[y * kW + x], exact + 1e-4);
      EXPECT_GE(d[y * kW + x], exact / 1.0824 / 1.0824 - 1e-4);
    }
  }
  const std::vector<float> none = distance_to_mask(std::vector<std::uint8_t>(kW * kH, 0), kW, kH);
  EXPECT_TRUE(std::isinf(none[0]));
}

TEST(ImageMask, AMaskOfTheWrongSizeIsRefused) {
  EXPECT_THROW(open_mask(std::vector<std::uint8_t>(10, 0), kW, kH, 1), Error);
  EXPECT_THROW(open_mask(std::vector<std::uint8_t>(kW * kH, 0), kW, kH, -1), Error);
  EXPECT_THROW(distance_to_mask(std::vector<std::uint8_t>(10, 0), kW, kH), Error);
}

}  // namespace
}  // namespace lmk
