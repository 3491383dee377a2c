// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The viewpoint and occlusion benchmarks' scenes (issue #16): a generated scene seen from a new
// place, or with objects that hide part of each landmark instance. Both change only what the
// sensor sees; the ground-truth boxes stay as make_scene placed them.

#include <cstdint>
#include <map>
#include <string>

#include "lmk/landmark/landmark.h"
#include "lmk/sim/instance_visibility.h"
#include "lmk/sim/scene_types.h"

namespace lmk {

/// Moves the scene's sensor to a random_viewpoint of `range` around its first in-context instance,
/// with the generator's own sensor position as the reference direction (where landmarks are
/// demonstrated from). A viewpoint from which the sensor sees less than half of that instance is
/// drawn again, up to `attempts` times; the least hidden one is kept. Deterministic in `seed`.
void view_from_random_viewpoint(GeneratedScene& scene,
                                const std::map<std::string, Landmark>& captured, std::uint64_t seed,
                                const ViewpointRange& range = {}, int attempts = 12);

/// Where occluders go and how much they hide.
struct OcclusionRange {
  double max_hidden = 0.6;      ///< each hides U(0, max_hidden) of what the sensor saw
  double touching_share = 0.5;  ///< the share of occluders that touch the instance
  double max_gap = 0.35;        ///< the farthest a non-touching occluder stands in front, m
  int max_instances_per_landmark = 2;
};

/// Adds, for each of the first instances of every in-context landmark, a box standing between the
/// sensor and the instance: touching it (within a centimetre of the landmark's points, inside its
/// empty margin, as a cup against a bowl) or up to max_gap in front. Its height is drawn, and its
/// sideways offset is bisected so that it hides a drawn fraction of the landmark points the sensor
/// saw (the whole fraction when the box cannot hide that much). Deterministic in `seed`.
void add_occluders(GeneratedScene& scene, const std::map<std::string, Landmark>& captured,
                   std::uint64_t seed, const OcclusionRange& range = {});

}  // namespace lmk
