// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Step 4 of the reference FindLandmark: one candidate per seed, by PCL's ICP. Internal.

#include <atomic>

#include "lmk/landmark/find_landmark.h"
#include "lmk/landmark/landmark_index.h"
#include "lmk/landmark/scene_index.h"

namespace lmk::detail {

/// What every search method gets: the preprocessed scene, the landmark, both indexed, the seeds.
struct SearchInput {
  const SceneIndex& index;
  const PointCloud& scene;  ///< the points the seeds index: fine (reference) or coarse (fast)
  const Landmark& landmark;
  const LandmarkIndex& prepared;  ///< the landmark's own work, built for these settings
  SceneView scene_view;
  LandmarkView landmark_view;
  const Indices& seeds;  ///< indices into `scene`
  const ErrorMetric& metric;
  double threshold;  ///< the error threshold the search applies, m
  const FindSettings& settings;
};

/// One candidate per seed, in seed order: the landmark centred on the seed with its capture
/// orientation, aligned by pcl::IterativeClosestPoint (settings.reference.icp_iterations, no
/// correspondence distance limit, PCL's default convergence test, as the authors ran it), then
/// scored.
std::vector<Match> reference_candidates(const SearchInput& input);

}  // namespace lmk::detail
