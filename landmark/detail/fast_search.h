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

#include "lmk/landmark/detail/search_method.h"

namespace lmk::detail {

/// The fast method's steps: seeds near relief (relief_seeds.h), then the stages above.
const SearchMethodSteps& fast_search_steps();

/// Stages 4 and 5 for one pose: fine alignment from T_scene_capture, then the Ceres polish
/// whatever the error, scored by input.metric. `input.seeds` may be empty.
Match fast_align_and_polish(const SearchInput& input, const Eigen::Isometry3d& T_scene_capture);

}  // namespace lmk::detail
