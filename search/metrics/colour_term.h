// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The colour term of a candidate's error (issue #35, "Colour"; SelectionSettings::colour_weight):
// beyond the paper, which compares shapes only and so cannot tell a red cup from a blue one.
//
// Each landmark point with a colour, once the candidate's pose has moved it, is projected into the
// scene's image and paired with the closest hue among the pixels around it that measured a surface
// within the support distance of it. The term is the pairs' mean chroma distance
// (geometry/chroma.h): a change of brightness between the demonstration and the scene leaves it
// unchanged. Landmark points with no such pixel (hidden behind another surface, out of view) say
// nothing of colour and are not paired.

#include <Eigen/Geometry>
#include <cstddef>

#include "lmk/search/find_settings.h"
#include "lmk/search/metrics/error_metrics.h"

namespace lmk {
class SceneIndex;
}

namespace lmk::detail {

struct ColourComparison {
  double difference = 0.0;   ///< mean chroma distance over the pairs
  std::size_t pairs = 0;     ///< landmark points paired with a coloured scene point
  std::size_t coloured = 0;  ///< landmark points with a chroma (not too dark, not clipped)
};

/// The colour comparison of the landmark at T_scene_capture with the scene's image, pairing within
/// `support` metres. Not measured (no pairs) when either has no colour.
ColourComparison compare_colours(const SceneView& scene, const LandmarkView& landmark,
                                 const Eigen::Isometry3d& T_scene_capture, double support);

/// Whether `c` holds enough pairs to judge a candidate's colour: a tenth of the landmark's coloured
/// points and at least 10, so that a sliver seen at an image edge or a few stray points do not
/// speak for the whole landmark.
bool colour_is_measured(const ColourComparison& c);

/// Adds the colour term to `terms` (ErrorTerms::colour) when `c` is measured: `weight` x
/// `threshold` x max(0, difference - tolerance), in the metric's unit, so that a weight of 1
/// charges a whole threshold for a chroma difference of 1 beyond the tolerance.
void add_colour_term(const ColourComparison& c, double weight, double tolerance, double threshold,
                     ErrorTerms& terms);

/// `shape`, the search's metric, with the colour term added to each error under the threshold (one
/// over it is turned down whatever its colour), when the search
/// weighs colour (resolved `settings`) and `landmark` and `scene` both have it; else `shape` as it
/// is, so that a search without colour gives the answers it gave before colour existed. Pairs are
/// sought within two leaves of the coarser of the landmark's and the scene's.
ErrorMetric with_colour_term(ErrorMetric shape, const FindSettings& settings,
                             const Landmark& landmark, const SceneIndex& scene);

}  // namespace lmk::detail
