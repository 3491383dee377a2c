// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/fast/coarse_fit.h"

namespace lmk::detail {

CoarseFit coarse_fit(const std::vector<Eigen::Vector3f>& points, const IcpTarget& target,
                     const Eigen::Isometry3d& start, const IcpSettings& settings,
                     const CoarseScore& score, const CoarseScore& test, double hopeless_above) {
  const auto scored = [&](const IcpResult& r, int iterations) {
    return CoarseFit{r.T_target_source, iterations,
                     score ? score(r.T_target_source.cast<float>()) : 0.0, false};
  };
  if (!score || settings.termination.max_iterations <= kFirstCoarseSteps) {
    const IcpResult r = icp(points, target, start, settings);
    return scored(r, r.iterations);
  }
  IcpSettings first = settings;
  first.termination.max_iterations = kFirstCoarseSteps;
  const IcpResult r = icp(points, target, start, first);
  // An ICP that converged or gave up (too few correspondences) would end the same way again.
  if (r.converged || r.iterations < kFirstCoarseSteps) return scored(r, r.iterations);
  const double tested = (test ? test : score)(r.T_target_source.cast<float>());
  if (tested > hopeless_above) return {r.T_target_source, r.iterations, tested, true};
  IcpSettings rest = settings;
  rest.termination.max_iterations = settings.termination.max_iterations - kFirstCoarseSteps;
  const IcpResult more = icp(points, target, r.T_target_source, rest);
  return scored(more, r.iterations + more.iterations);
}

}  // namespace lmk::detail
