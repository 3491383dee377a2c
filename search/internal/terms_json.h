// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The JSON form of a match's error terms, shared by `lmk find --json` and the evaluation cache and
// reports. Header-only; internal/: shared within lmk, not installed.

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "lmk/json/pose_json.h"
#include "lmk/search/metrics/error_metrics.h"

namespace lmk::detail {

/// Every term, in one schema whatever the metric: the terms a metric does not measure are written
/// as they always were, coverage and empty_space_observed null and the counts 0; the colour terms
/// only where colour was compared.
inline nlohmann::json terms_to_json(const ErrorTerms& t) {
  const SupportTerms support = t.support.value_or(SupportTerms{});
  const EmptySpaceTerms empty = t.empty_space.value_or(EmptySpaceTerms{});
  nlohmann::json j = {{"scene_to_landmark_sum", t.scene_to_landmark_sum},
                      {"scene_to_landmark_count", t.scene_to_landmark_count},
                      {"landmark_to_scene_sum", t.landmark_to_scene_sum},
                      {"landmark_to_scene_count", t.landmark_to_scene_count},
                      {"scene_points_in_box", t.scene_points_in_box},
                      {"coverage", finite_or_null(t.coverage())},
                      {"empty_space_probes", empty.probes},
                      {"empty_space_violations", empty.violations},
                      {"empty_space_violation_mean", empty.violation_mean},
                      {"unseen_points", support.unseen_points},
                      {"seen_through_points", support.seen_through_points},
                      {"empty_space_observed", finite_or_null(empty.observed)},
                      {"range_scale", t.range_scale}};
  if (t.colour) {
    j["colour_difference"] = t.colour->difference;
    j["colour_points"] = t.colour->points;
    j["colour_penalty"] = t.colour->penalty;
  }
  return j;
}

/// The inverse of terms_to_json; `error` is recomputed from the sums and counts.
inline ErrorTerms terms_from_json(const nlohmann::json& j, const std::string& where) {
  const auto number = [&](const char* key) {
    const nlohmann::json& v = json_field(j, key, where);
    if (!v.is_number()) throw Error(where + "." + key + ": must be a number");
    return v.get<double>();
  };
  const auto count = [&](const char* key) {
    const nlohmann::json& v = json_field(j, key, where);
    if (!v.is_number_unsigned()) throw Error(where + "." + key + ": must be a count");
    return v.get<std::size_t>();
  };
  ErrorTerms t;
  t.scene_to_landmark_sum = number("scene_to_landmark_sum");
  t.scene_to_landmark_count = count("scene_to_landmark_count");
  t.landmark_to_scene_sum = number("landmark_to_scene_sum");
  t.landmark_to_scene_count = count("landmark_to_scene_count");
  t.scene_points_in_box = count("scene_points_in_box");
  // A metric measured support where it wrote a coverage, and tested empty space where it probed
  // (or observed) any.
  const nlohmann::json& coverage = json_field(j, "coverage", where);
  if (!coverage.is_null()) {
    SupportTerms& support = t.support.emplace();
    support.coverage = number("coverage");
    // Written since the sensor metric; earlier files have neither.
    if (j.contains("unseen_points")) support.unseen_points = count("unseen_points");
    if (j.contains("seen_through_points"))
      support.seen_through_points = count("seen_through_points");
  }
  EmptySpaceTerms empty;
  empty.probes = count("empty_space_probes");
  empty.violations = count("empty_space_violations");
  empty.violation_mean = number("empty_space_violation_mean");
  if (j.contains("empty_space_observed") && !j["empty_space_observed"].is_null())
    empty.observed = number("empty_space_observed");
  if (empty.probes > 0 || empty.violations > 0 || !std::isnan(empty.observed))
    t.empty_space = empty;
  // Written since threshold_range; earlier files were never scaled.
  if (j.contains("range_scale")) {
    t.range_scale = number("range_scale");
    if (!(t.range_scale > 0.0 && t.range_scale <= 1.0))
      throw Error(where + ".range_scale: must be in (0, 1]");
  }
  if (j.contains("colour_points")) {  // written since the colour term, where it was measured
    ColourTerms& colour = t.colour.emplace();
    colour.difference = number("colour_difference");
    colour.points = count("colour_points");
    colour.penalty = number("colour_penalty");
    if (!(colour.penalty >= 0.0)) throw Error(where + ".colour_penalty: must be non-negative");
  }
  t.finish();
  return t;
}

}  // namespace lmk::detail
