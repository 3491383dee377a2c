// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The coarse scores of the built-in metrics (ErrorMetric::coarse_score): what the fast search
// ranks and prunes its coarsely aligned candidates by (step 3 of fast_search.h). Each estimates
// its metric cheaply, in the metric's unit. Internal.

#include "lmk/search/metrics/error_metrics.h"

namespace lmk::detail {

/// The mean distance of the sparse model's points to the scene surface (mean_surface_distance()),
/// in metres: the visibility metrics' and the paper's. With `hide_occluded`, points hidden behind
/// a nearer surface outside the candidate's box do not count, as the projective metric hides
/// them.
CoarseScoreFactory surface_distance_coarse_score(bool hide_occluded);

/// The sensor metric's own fit, in sigma: the coarse model's noise-scaled residuals with projective
/// visibility (sensor_fit()), plus the space the landmark needs free where the scene's sensor
/// measured a surface (empty_space_penalty()) -- the sharpest test at range, where the fit's
/// residuals drown in noise, so that a far instance, noisy in millimetres, still ranks first.
CoarseScoreFactory sensor_coarse_score();

}  // namespace lmk::detail
