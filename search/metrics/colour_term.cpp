// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/metrics/colour_term.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lmk/geometry/chroma.h"
#include "lmk/geometry/range_image.h"
#include "lmk/landmark/landmark.h"
#include "lmk/search/scene_index.h"

namespace lmk::detail {
namespace {

// Each landmark point takes the closest hue among the scene's pixels around where it projects, a
// grid of kColourSamples x kColourSamples spanning the support distance either way: a textured
// surface (print on a box, a label) matched a few millimetres off pairs a point with its
// neighbour's colour, while a surface of another colour has no close hue anywhere near. Looking the
// pixels up in the scene's image costs no index of its own.
constexpr int kColourSamples = 5;

// std::lround, inline: it is a libm call on the baseline x86-64 instruction set, and the colour
// term takes two per pixel looked at, 25 per landmark point. Halves go away from zero, as there;
// x - trunc(x) is exact. A coordinate far off any image (a point projected from near the sensor's
// plane) is -1, off the image too, rather than an integer conversion out of range.
long pixel_index(double x) {
  if (!(std::abs(x) < 1e9)) return -1;
  const auto truncated = static_cast<long>(x);
  const double rest = x - static_cast<double>(truncated);
  return truncated + (rest >= 0.5 ? 1 : 0) - (rest <= -0.5 ? 1 : 0);
}

// The closest hue to `mine` among the pixels around `pixel` whose depth lies within `support` of
// `depth`: the surface the point lies on, not one in front of it or behind.
double closest_hue(const RangeImage& image, const Eigen::Vector3f& mine,
                   const Eigen::Vector2d& pixel, double depth, double support) {
  const PinholeIntrinsics& k = image.intrinsics();
  const double step = std::max(1.0, support * k.fx / depth / (kColourSamples / 2));
  // The grid's columns and rows, each rounded once (not once per pixel), those off the image
  // left out.
  long columns[kColourSamples], rows[kColourSamples];
  int n_columns = 0, n_rows = 0;
  for (int d = -kColourSamples / 2; d <= kColourSamples / 2; ++d) {
    const long u = pixel_index(pixel.x() + d * step);
    const long v = pixel_index(pixel.y() + d * step);
    if (u >= 0 && u < k.width) columns[n_columns++] = u;
    if (v >= 0 && v < k.height) rows[n_rows++] = v;
  }
  // chroma_distance's square root taken once, of the least squared distance: the root is monotonic,
  // so the root of the least is the least root.
  float best = std::numeric_limits<float>::infinity();
  for (int r = 0; r < n_rows; ++r) {
    const std::size_t row_start =
        static_cast<std::size_t>(rows[r]) * static_cast<std::size_t>(k.width);
    for (int c = 0; c < n_columns; ++c) {
      const std::size_t i = row_start + static_cast<std::size_t>(columns[c]);
      const float measured = image.depths()[i];
      if (!(std::abs(measured - depth) <= support)) continue;  // NaN: nothing measured
      if (const auto theirs = chroma_of(image.colours()[i])) {
        best = std::min(best, (mine - *theirs).squaredNorm());
      }
    }
  }
  return static_cast<double>(std::sqrt(best));
}

}  // namespace

ColourComparison compare_colours(const SceneView& scene, const LandmarkView& landmark,
                                 const Eigen::Isometry3d& T_scene_capture, double support) {
  ColourComparison c;
  const RangeImage* image = scene.index.range_image();
  const PointCloud& points = landmark.points;
  if (!points.has_colors() || !image || image->colours().empty()) return c;
  const Eigen::Isometry3f T = T_scene_capture.cast<float>();
  double sum = 0.0;
  for (std::size_t j = 0; j < points.size(); ++j) {
    const auto mine = chroma_of(points.colors[j]);
    if (!mine) continue;
    ++c.coloured;
    const Eigen::Vector3f p = T * points.points[j];
    const auto pixel = image->project(p);
    if (!pixel) continue;
    const double best = closest_hue(*image, *mine, *pixel, image->depth_of(p), support);
    if (!std::isfinite(best)) continue;
    sum += best;
    ++c.pairs;
  }
  if (c.pairs > 0) c.difference = sum / static_cast<double>(c.pairs);
  return c;
}

bool colour_is_measured(const ColourComparison& c) {
  return c.pairs >= 10 && 10 * c.pairs >= c.coloured;
}

void add_colour_term(const ColourComparison& c, double weight, double tolerance, double threshold,
                     ErrorTerms& terms) {
  if (!colour_is_measured(c)) return;
  terms.colour = ColourTerms{c.difference, c.pairs,
                             weight * threshold * std::max(0.0, c.difference - tolerance)};
  terms.finish();
}

ErrorMetric with_colour_term(ErrorMetric shape, const FindSettings& settings,
                             const Landmark& landmark, const SceneIndex& scene) {
  const SelectionSettings& s = settings.selection;
  if (!(s.colour_weight > 0.0) || !landmark.points.has_colors() || !scene.has_colours()) {
    return shape;
  }
  const double support = 2.0 * std::max(landmark.settings.leaf_size, scene.settings().leaf_size);
  const double threshold = *s.threshold;
  shape.evaluate = [evaluate = std::move(shape.evaluate), s, support, threshold](
                       const SceneView& view, const LandmarkView& points,
                       const Eigen::Isometry3d& T_scene_capture) {
    ErrorTerms terms = evaluate(view, points, T_scene_capture);
    // A shape over the threshold is turned down whatever its colour, and it outranks no candidate
    // under it: the colour of most candidates need not be looked at.
    if (!(terms.error < threshold)) return terms;
    add_colour_term(compare_colours(view, points, T_scene_capture, support), s.colour_weight,
                    s.colour_tolerance, threshold, terms);
    return terms;
  };
  return shape;
}

}  // namespace lmk::detail
