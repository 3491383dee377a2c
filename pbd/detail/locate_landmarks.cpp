// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pbd/detail/locate_landmarks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lmk/geometry/error.h"
#include "lmk/geometry/stopwatch.h"
#include "lmk/search/find_landmark.h"
#include "lmk/search/scene_index.h"

namespace lmk::detail {

namespace {

// The landmarks some step is relative to, in the order the program declares them.
std::vector<const ProgramLandmark*> used_landmarks(const Program& program) {
  std::vector<const ProgramLandmark*> out;
  for (const std::string& name : landmarks_used(program)) out.push_back(program.landmark(name));
  return out;
}

// The matches the policy allows, in the order it prefers them.
std::vector<const Match*> eligible_matches(const std::vector<Match>& matches,
                                           const ProgramLandmark& landmark, InstancePolicy policy,
                                           const PlanSettings& settings) {
  std::vector<const Match*> out;
  for (const Match& m : matches) out.push_back(&m);  // already by increasing error
  if (policy == InstancePolicy::kBestError || !landmark.demonstration) return out;
  const Eigen::Vector3d demonstrated = landmark.demonstration->translation();
  if (policy == InstancePolicy::kDemonstratedHeight) {
    out.erase(std::remove_if(out.begin(), out.end(),
                             [&](const Match* m) {
                               return std::abs(m->box.center().z() - demonstrated.z()) >
                                      settings.height_tolerance;
                             }),
              out.end());
  } else {
    std::stable_sort(out.begin(), out.end(), [&](const Match* a, const Match* b) {
      return (a->box.center() - demonstrated).norm() < (b->box.center() - demonstrated).norm();
    });
  }
  return out;
}

// The matches sure enough to act on (passes_confidence()), in the order given.
std::vector<const Match*> confident_matches(const std::vector<const Match*>& matches, double cut) {
  std::vector<const Match*> out;
  for (const Match* m : matches) {
    if (passes_confidence(m->confidence.probability, cut)) out.push_back(m);
  }
  return out;
}

std::string no_eligible_reason(const FindResult& result, std::size_t found, InstancePolicy policy,
                               const ProgramLandmark& landmark, const PlanSettings& settings) {
  if (found == 0) {
    const std::string why = describe_rejections(result.stats);
    return why.empty() ? "no match" : "no match (" + why + ")";
  }
  char text[160];
  std::snprintf(text, sizeof(text),
                "%zu match(es), none within %.0f mm of the demonstrated height %.3f m (%s)", found,
                1000.0 * settings.height_tolerance, landmark.demonstration->translation().z(),
                instance_policy_name(policy));
  return text;
}

// A landmark that may only be taken at its demonstrated height is searched only there: the work
// volume narrowed to the slab its box can occupy at that height. Instances elsewhere (the top of a
// box standing on the table, for an empty table patch) would only crowd the search's finalists.
FindResult find_at_height(const PointCloud& scene, const Landmark& landmark,
                          const ProgramLandmark& entry, const FindSettings& find,
                          const PlanSettings& settings) {
  FindSettings narrowed = find;
  const double z = entry.demonstration->translation().z();
  // Half the box's vertical extent however it is turned, plus the tolerance and a leaf of slack.
  const Eigen::Matrix3d R = entry.demonstration->linear();
  const double half = 0.5 * (R.row(2).cwiseAbs() * landmark.box.size)(0);
  const double slab = 2.0 * (half + settings.height_tolerance + find.scene.leaf_size);
  Box volume = *find.scene.work_volume;
  const Eigen::Vector3d centre = volume.center();
  volume.pose.translation() = Eigen::Vector3d(centre.x(), centre.y(), z);
  volume.size.z() = slab;
  narrowed.scene.work_volume = volume;
  return find_landmark(scene, landmark, narrowed);
}

}  // namespace

LocatedLandmark choose(const Candidates& c, std::size_t k) {
  LocatedLandmark l = c.located;
  l.match = c.matches[k];
  l.T_base_landmark = l.match.box.pose;
  if (c.entry->demonstration) {
    l.T_base_landmark.linear() = nearest_symmetric_rotation(
        l.T_base_landmark.linear(), c.entry->demonstration->linear(), c.entry->symmetry);
  }
  return l;
}

std::optional<Refusal> locate_landmarks(const Program& program,
                                        const std::map<std::string, Landmark>& landmarks,
                                        const PointCloud& scene, const PlanSettings& settings,
                                        std::vector<Candidates>& out) {
  const std::vector<const ProgramLandmark*> used = used_landmarks(program);
  if (used.empty()) return std::nullopt;
  FindSettings find = settings.find;
  find.scene.base_frame = true;
  if (!find.scene.work_volume) find.scene.work_volume = settings.workspace;
  // Built on first use: landmarks searched only at their demonstrated height index their own slab.
  std::optional<SceneIndex> index;
  for (const ProgramLandmark* entry : used) {
    const auto it = landmarks.find(entry->name);
    if (it == landmarks.end()) {
      throw Error("plan: program '" + program.name + "' declares landmark '" + entry->name +
                  "', but it was not loaded");
    }
    if (settings.progress) settings.progress("locating '" + entry->name + "'");
    const Stopwatch stopwatch;
    const InstancePolicy policy = entry->select.value_or(settings.policy);
    if (policy != InstancePolicy::kDemonstratedHeight && !index) {
      index.emplace(scene, find.scene);
    }
    const FindResult result = policy == InstancePolicy::kDemonstratedHeight
                                  ? find_at_height(scene, it->second, *entry, find, settings)
                                  : find_landmark(*index, it->second, find);
    const std::vector<const Match*> eligible =
        eligible_matches(result.matches, *entry, policy, settings);
    if (eligible.empty()) {
      return LandmarkNotFound{
          entry->name, no_eligible_reason(result, result.matches.size(), policy, *entry, settings)};
    }
    const std::vector<const Match*> sure = confident_matches(eligible, settings.min_confidence);
    if (sure.empty()) {
      const MatchConfidence& c = eligible.front()->confidence;
      return LandmarkDoubtful{entry->name,
                              c.probability,
                              settings.min_confidence,
                              c.competitor,
                              describe_doubt(c, eligible.front()->box),
                              eligible.front()->box};
    }
    Candidates c;
    c.entry = entry;
    for (const Match* m : sure) {
      c.matches.push_back(*m);
      c.matches.back().aligned_points = PointCloud();  // not needed past the search
    }
    c.located.name = entry->name;
    c.located.found = result.matches.size();
    c.located.metric = result.stats.metric;
    c.located.eligible = eligible.size();
    c.located.policy = policy;
    c.located.seconds = stopwatch.seconds();
    out.push_back(std::move(c));
  }
  return std::nullopt;
}

}  // namespace lmk::detail
