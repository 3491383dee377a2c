// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Chroma: the colour of a point without its brightness (issue #35, "Colour").
//
// A surface's RGB changes with the light falling on it and with the camera's exposure; its
// chromaticity, each channel's share of their sum, does not change when every channel is scaled
// alike. Comparing chromaticities is what lets a landmark demonstrated under one light tell red
// from blue under another. A pixel too dark to have a reliable hue, or clipped at white, has no
// chroma worth comparing.

#include <Eigen/Core>
#include <optional>

#include "lmk/geometry/point_cloud.h"

namespace lmk {

/// Below this sum of the three 8-bit channels a pixel's hue is mostly sensor noise: one count of
/// noise moves a channel's share of a sum of 60 by almost 2%.
inline constexpr int kMinChromaBrightness = 60;

/// The largest distance between two chromaticities: pure red to pure green (sqrt 2).
inline constexpr double kMaxChromaDistance = 1.4142135623730951;

/// Each channel's share of r + g + b (they sum to 1); nothing for a pixel darker than
/// kMinChromaBrightness, or clipped (every channel at 255), whose hue the sensor did not measure.
inline std::optional<Eigen::Vector3f> chroma_of(const Color& c) {
  const int sum = int{c.r} + int{c.g} + int{c.b};
  if (sum < kMinChromaBrightness || (c.r == 255 && c.g == 255 && c.b == 255)) return std::nullopt;
  return Eigen::Vector3f(c.r, c.g, c.b) / static_cast<float>(sum);
}

/// The Euclidean distance between two chromaticities, 0 to kMaxChromaDistance: about 0.9 from a
/// saturated red to a saturated blue, 0.3 from red to orange, a few hundredths between two
/// views of one surface.
inline double chroma_distance(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  return static_cast<double>((a - b).norm());
}

}  // namespace lmk
