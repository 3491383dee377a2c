// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Steps 1-2 of a plan (plan.h): every landmark a program step uses, found in the scene, with the
// instances its policy allows (InstancePolicy) and that are sure enough to act on, or the refusal.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/point_cloud.h"
#include "lmk/landmark/landmark.h"
#include "lmk/pbd/plan.h"
#include "lmk/pbd/program.h"
#include "lmk/search/find_result.h"

namespace lmk::detail {

// A landmark's eligible instances, in the order its policy prefers them.
struct Candidates {
  const ProgramLandmark* entry = nullptr;
  std::vector<Match> matches;
  LocatedLandmark located;  ///< everything but the chosen match
};

/// The located landmark for one of its candidates: the match's box, turned within the landmark's
/// symmetry to the orientation nearest the demonstration.
LocatedLandmark choose(const Candidates& c, std::size_t k);

/// Steps 1-2 of execution: every landmark a step uses, with its eligible instances, into `out`;
/// or the refusal (a landmark not found, or found too doubtfully to act on).
std::optional<Refusal> locate_landmarks(const Program& program,
                                        const std::map<std::string, Landmark>& landmarks,
                                        const PointCloud& scene, const PlanSettings& settings,
                                        std::vector<Candidates>& out);

}  // namespace lmk::detail
