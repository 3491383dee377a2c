// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The search methods behind one interface. find_landmark chooses the method once, from
// FindSettings::method, and asks it for the steps that differ between methods: which scene points
// seed the search (step 3), the candidates of those seeds (step 4), and whether selection drops a
// match inside a better one's box. Everything else (the scene's preprocessing, steps 5-6) is
// shared. Internal.

#include <vector>

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
  double threshold;  ///< the error threshold the search applies, in the metric's own unit
  const FindSettings& settings;  ///< resolved (FindSettings::resolved())
};

/// A method's candidates: those it keeps for selection, and those its own non-max suppression
/// removed (rivals of the matches, match_confidence.h; returned to the caller only when
/// settings.execution.keep_suppressed asks for them).
struct CandidateSet {
  std::vector<Match> kept;
  std::vector<Match> suppressed;
};

class SearchMethodSteps {
 public:
  virtual ~SearchMethodSteps() = default;

  /// The scene points the method seeds from and aligns to.
  virtual const PointCloud& seed_cloud(const SceneIndex& index) const = 0;

  /// Step 3: the seeds, indices into seed_cloud(index), for resolved `settings`.
  virtual Indices seeds(const SceneIndex& index, const LandmarkIndex& landmark,
                        const FindSettings& settings) const = 0;

  /// Step 4: candidate matches in a deterministic order, whatever the thread count. The method's
  /// own counts and timings go to `stats`.
  virtual CandidateSet candidates(const SearchInput& input, SearchStats& stats) const = 0;

  /// Whether selection drops a match whose box centre lies in a better match's box.
  virtual bool suppresses_overlaps(const FindSettings& settings) const = 0;
};

/// The steps of `method`; each method is stateless, so one instance serves every search.
const SearchMethodSteps& search_method_steps(SearchMethod method);

}  // namespace lmk::detail
