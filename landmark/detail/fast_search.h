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
// 5. Non-max suppression, then Ceres robust refinement with the empty-space penalty for the
//    suppression's winners that are near the threshold.

#include <vector>

#include "lmk/landmark/detail/reference_search.h"

namespace lmk::detail {

struct FastSearchStats {
  std::size_t poses = 0;        ///< poses voted by the seeds (after the tilt limit)
  std::size_t clusters = 0;     ///< after merging
  std::size_t refined = 0;      ///< survivors of the coarse pruning
  double seconds_vote = 0.0;    ///< steps 1 and 2
  double seconds_coarse = 0.0;  ///< step 3
  double seconds_fine = 0.0;    ///< steps 4 and 5
};

/// Candidates in a deterministic order (by cluster rank), whatever the thread count.
std::vector<Match> fast_candidates(const SearchInput& input, FastSearchStats& stats);

}  // namespace lmk::detail
