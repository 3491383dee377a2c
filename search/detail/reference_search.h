// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Steps 3-4 of the reference FindLandmark: random seeds, one candidate per seed by PCL's ICP.
// Internal.

#include "lmk/search/search_method.h"

namespace lmk::detail {

/// The paper's steps 3-4: a seeded random sample of sample_fraction of the fine points (at most
/// max_seeds), and one candidate per seed, in seed order: the landmark centred on the seed with its
/// capture orientation, aligned by pcl::IterativeClosestPoint (settings.reference.icp_iterations,
/// no correspondence distance limit, PCL's default convergence test, as the authors ran it), then
/// scored. No overlap suppression: the paper's non-max suppression looks at box centres only.
const SearchMethodSteps& reference_search_steps();

}  // namespace lmk::detail
