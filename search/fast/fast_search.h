// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The fast search (method "fast"), coarse to fine (docs/landmarks.md, "The fast search").
// Internal.
//
// 1. Seeds: each seed scene point votes with point pair features for full 6-DoF poses
//    (point_pair_voting.h), so every orientation is reachable; poses tilted beyond the limit are
//    dropped unless every orientation is searched.
// 2. Clustering: nearby poses merge, their votes add up; the best-voted clusters go on.
// 3. Coarse alignment: a few point-to-plane ICP steps of the landmark's coarse points against the
//    scene's closest-point grid, then a cheap score; hopeless candidates are pruned.
// 4. Fine alignment of the survivors (ICP on up to 1000 landmark points) and scoring with the
//    chosen metric.
// 5. Polish: non-max suppression, then Ceres robust refinement with the empty-space penalty for
//    the suppression's winners that are near the threshold.
//
// Each stage is one function of fast_search.cpp that returns a small stage result.

#include "lmk/search/search_method.h"

namespace lmk::detail {

/// The fast method's steps: seeds near relief (relief_seeds.h), then the stages above; aligned
/// at a given pose, stages 4 and 5 from it.
const SearchMethodSteps& fast_search_steps();

}  // namespace lmk::detail
