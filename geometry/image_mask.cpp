// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/image_mask.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lmk/geometry/error.h"

namespace lmk {
namespace {

// The summed-area table of a mask: entry (y, x) of a (height + 1) x (width + 1) table holds the
// count of set pixels above and left of pixel (y, x).
class SummedArea {
 public:
  SummedArea(const std::vector<std::uint8_t>& mask, int width, int height)
      : stride_(width + 1), sums_(static_cast<std::size_t>(width + 1) * (height + 1), 0) {
    for (int y = 0; y < height; ++y) {
      long row = 0;
      for (int x = 0; x < width; ++x) {
        row += mask[static_cast<std::size_t>(y) * width + x] ? 1 : 0;
        at(y + 1, x + 1) = at(y, x + 1) + row;
      }
    }
  }
  // Set pixels in rows [y0, y1) and columns [x0, x1).
  long count(int x0, int y0, int x1, int y1) const {
    return at(y1, x1) - at(y0, x1) - at(y1, x0) + at(y0, x0);
  }

 private:
  long& at(int y, int x) { return sums_[static_cast<std::size_t>(y) * stride_ + x]; }
  long at(int y, int x) const { return sums_[static_cast<std::size_t>(y) * stride_ + x]; }
  int stride_;
  std::vector<long> sums_;
};

// For each pixel, whether the square of `radius` about it, clipped to the image, holds `wanted`
// set pixels: all of them (erosion, `all`) or at least one (dilation).
std::vector<std::uint8_t> square_test(const std::vector<std::uint8_t>& mask, int width, int height,
                                      int radius, bool all) {
  const SummedArea sums(mask, width, height);
  std::vector<std::uint8_t> out(mask.size(), 0);
  for (int y = 0; y < height; ++y) {
    const int y0 = std::max(0, y - radius), y1 = std::min(height, y + radius + 1);
    for (int x = 0; x < width; ++x) {
      const int x0 = std::max(0, x - radius), x1 = std::min(width, x + radius + 1);
      const long set = sums.count(x0, y0, x1, y1);
      const long area = static_cast<long>(x1 - x0) * (y1 - y0);
      out[static_cast<std::size_t>(y) * width + x] = all ? set == area : set > 0;
    }
  }
  return out;
}

}  // namespace

namespace {
void check_mask(const std::vector<std::uint8_t>& mask, int width, int height, const char* what) {
  if (width < 0 || height < 0 || mask.size() != static_cast<std::size_t>(width) * height)
    throw Error(std::string(what) + ": the mask is not " + std::to_string(width) + " x " +
                std::to_string(height));
}
}  // namespace

std::vector<std::uint8_t> open_mask(const std::vector<std::uint8_t>& mask, int width, int height,
                                    int radius) {
  check_mask(mask, width, height, "open_mask");
  if (radius < 0) throw Error("open_mask: the radius must not be negative");
  // Erosion keeps the centres of squares wholly set (clipping to the image counts beyond its edge
  // as set); dilating those by the same square restores the regions they came from.
  return square_test(square_test(mask, width, height, radius, true), width, height, radius, false);
}

std::vector<float> distance_to_mask(const std::vector<std::uint8_t>& mask, int width, int height) {
  check_mask(mask, width, height, "distance_to_mask");
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const float diagonal = static_cast<float>(std::sqrt(2.0));
  std::vector<float> d(mask.size(), kInf);
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i]) d[i] = 0.0f;
  const auto relax = [&](int x, int y, int dx, int dy, float step) {
    const int nx = x + dx, ny = y + dy;
    if (nx < 0 || ny < 0 || nx >= width || ny >= height) return;
    float& here = d[static_cast<std::size_t>(y) * width + x];
    here = std::min(here, d[static_cast<std::size_t>(ny) * width + nx] + step);
  };
  // Forward over the neighbours above and left, then backward over those below and right.
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      relax(x, y, -1, 0, 1.0f);
      relax(x, y, 0, -1, 1.0f);
      relax(x, y, -1, -1, diagonal);
      relax(x, y, 1, -1, diagonal);
    }
  }
  for (int y = height - 1; y >= 0; --y) {
    for (int x = width - 1; x >= 0; --x) {
      relax(x, y, 1, 0, 1.0f);
      relax(x, y, 0, 1, 1.0f);
      relax(x, y, 1, 1, diagonal);
      relax(x, y, -1, 1, diagonal);
    }
  }
  // The chamfer's worst excess over the Euclidean distance, sqrt(1 + (sqrt 2 - 1)^2), is met
  // along the direction tan = sqrt 2 - 1: dividing by it leaves a lower bound everywhere.
  constexpr float kChamferExcess = 1.0824f;
  for (float& v : d) v /= kChamferExcess;
  return d;
}

}  // namespace lmk
