// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One cluster's coarse alignment (step 3 of the fast search, docs/landmarks.md): ICP from the
// voted pose, scored by the metric's cheap score, stopped early when it cannot make the prune
// (measured in docs/cluster.md, "The coarse stage's hopeless clusters"). Internal.

#include <Eigen/Geometry>
#include <vector>

#include "lmk/registration/icp.h"
#include "lmk/search/metrics/error_metrics.h"

namespace lmk::detail {

/// ICP steps every cluster takes before the stop test.
inline constexpr int kFirstCoarseSteps = 2;
/// A cluster stops when its test score lies beyond the prune bound by more than this factor.
inline constexpr double kHopelessMargin = 1.1;
/// Landmark points the stop test scores: an eighth of the 400 the coarse stage aligns, since it
/// only has to tell the hopeless from the rest.
inline constexpr std::size_t kStopTestPoints = 50;

struct CoarseFit {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  int iterations = 0;    ///< ICP steps taken
  double score = 0.0;    ///< `score` at `pose` (0 without one); `test`'s where it stopped early
  bool stopped = false;  ///< by the stop test
};

/// ICP of `points` from `start` under `settings`, then `score` at the result. With a score and
/// more than kFirstCoarseSteps steps allowed, it first takes kFirstCoarseSteps steps and scores the
/// pose with `test` (a cheap version of `score`; `score` itself when empty): beyond
/// `hopeless_above`, it stops there, since the prune would drop it. Otherwise it goes on from that
/// pose with the remaining steps, which ends where one ICP of all the steps would (up to the
/// re-orthonormalisation between the two calls).
CoarseFit coarse_fit(const std::vector<Eigen::Vector3f>& points, const IcpTarget& target,
                     const Eigen::Isometry3d& start, const IcpSettings& settings,
                     const CoarseScore& score, const CoarseScore& test, double hopeless_above);

}  // namespace lmk::detail
