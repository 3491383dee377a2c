// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The search methods behind one interface. A method is chosen once, from FindSettings::method, and
// asked for everything that differs between methods: its defaults (FindSettings::resolved()), its
// own work on a landmark (LandmarkIndex), which scene points seed the search (step 3), the
// candidates of those seeds (step 4), one candidate aligned from a given pose (score_pose,
// find_near_pose), the landmark at the coarse leaf (the confidence's competitor check), and
// whether selection drops a match inside a better one's box. Everything else (the scene's
// preprocessing, steps 5-6, the confidence) is shared, and nothing outside a method asks which
// method it is. Internal.

#include <Eigen/Geometry>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "lmk/search/find_result.h"
#include "lmk/search/landmark_index.h"
#include "lmk/search/scene_index.h"

namespace lmk::detail {

/// What a method derives from the scene for one landmark besides the seeds (the fast method's
/// voting cloud), built while the seeds are chosen; the reference method needs nothing.
class MethodScene {
 public:
  virtual ~MethodScene() = default;
};

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
  /// The method's prepare_scene() for this search; null: candidates() makes what it needs.
  const MethodScene* method_scene;
};

/// A method's candidates: those it keeps for selection, and those its own non-max suppression
/// removed (rivals of the matches, match_confidence.h; returned to the caller only when
/// settings.execution.keep_suppressed asks for them).
struct CandidateSet {
  std::vector<Match> kept;
  std::vector<Match> suppressed;
};

/// What a method derives from a landmark alone, built once per LandmarkIndex (the fast method's
/// point pair model); the reference method needs nothing.
class MethodLandmark {
 public:
  virtual ~MethodLandmark() = default;
  /// Whether a search with `settings` (of this method) can use it: the settings it was built from
  /// are the same.
  virtual bool suits(const FindSettings& settings) const = 0;
  /// Those settings, for messages, as SearchMethodSteps::prepared_for() names them.
  virtual std::string built_for() const = 0;
};

class SearchMethodSteps {
 public:
  virtual ~SearchMethodSteps() = default;

  /// The method's defaults for what FindSettings leaves unset: the most seeds, and the metric.
  virtual std::size_t default_max_seeds() const = 0;
  virtual const char* default_metric() const = 0;

  /// Its own work on `landmark` for resolved `settings` (LandmarkIndex builds it once).
  virtual std::unique_ptr<const MethodLandmark> prepare(const Landmark& landmark,
                                                        const FindSettings& settings) const = 0;
  /// The settings prepare() depends on, for messages: "" when none, else ", coarse leaf 0.01 m and
  /// vote leaf fraction 0.05".
  virtual std::string prepared_for(const FindSettings& settings) const = 0;

  /// The scene points the method seeds from and aligns to.
  virtual const PointCloud& seed_cloud(const SceneIndex& index) const = 0;

  /// Step 3: the seeds, indices into seed_cloud(index), for resolved `settings`.
  virtual Indices seeds(const SceneIndex& index, const LandmarkIndex& landmark,
                        const FindSettings& settings) const = 0;

  /// Step 3's companion: the method's work on the scene for this landmark that the seeds do not
  /// need (the fast method's voting cloud and its grid). The search builds it beside the seeds,
  /// so that the serial steps of each fill the other's idle thread. Null when there is none.
  virtual std::unique_ptr<const MethodScene> prepare_scene(
      const SceneIndex& /*index*/, const LandmarkIndex& /*landmark*/) const {
    return nullptr;
  }

  /// Step 4: candidate matches in a deterministic order, whatever the thread count. The method's
  /// own counts and timings go to `stats`.
  virtual CandidateSet candidates(const SearchInput& input, SearchStats& stats) const = 0;

  /// One candidate aligned from `T_scene_capture` as the method aligns its own (`input.seeds`
  /// empty), and scored by input.metric: what score_pose and find_near_pose ask.
  virtual Match align_at(const SearchInput& input,
                         const Eigen::Isometry3d& T_scene_capture) const = 0;

  /// The landmark at the scene's coarse leaf (the confidence's competitor check): the method's own
  /// when it keeps one, else made in `storage`.
  virtual const PointCloud& coarse_landmark(const LandmarkIndex& prepared, const SceneIndex& index,
                                            PointCloud& storage) const = 0;

  /// Whether selection drops a match whose box centre lies in a better match's box.
  virtual bool suppresses_overlaps(const FindSettings& settings) const = 0;
};

/// The steps of `method`; each method is stateless, so one instance serves every search.
const SearchMethodSteps& search_method_steps(SearchMethod method);

}  // namespace lmk::detail
