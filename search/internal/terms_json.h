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

/// Every term; coverage is null for the metrics that do not measure it.
inline nlohmann::json terms_to_json(const ErrorTerms& t) {
  nlohmann::json j = {
      {"scene_to_landmark_sum", t.scene_to_landmark_sum},
      {"scene_to_landmark_count", t.scene_to_landmark_count},
      {"landmark_to_scene_sum", t.landmark_to_scene_sum},
      {"landmark_to_scene_count", t.landmark_to_scene_count},
      {"scene_points_in_box", t.scene_points_in_box},
      {"coverage", std::isnan(t.coverage) ? nlohmann::json(nullptr) : nlohmann::json(t.coverage)},
      {"empty_space_probes", t.empty_space_probes},
      {"empty_space_violations", t.empty_space_violations},
      {"empty_space_violation_mean", t.empty_space_violation_mean},
      {"unseen_points", t.unseen_points},
      {"seen_through_points", t.seen_through_points},
      {"empty_space_observed", std::isnan(t.empty_space_observed)
                                   ? nlohmann::json(nullptr)
                                   : nlohmann::json(t.empty_space_observed)},
      {"range_scale", t.range_scale}};
  // Only where colour was compared: a search without colour writes what it wrote before.
  if (t.colour_points > 0) {
    j["colour_difference"] = t.colour_difference;
    j["colour_points"] = t.colour_points;
    j["colour_penalty"] = t.colour_penalty;
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
  const nlohmann::json& coverage = json_field(j, "coverage", where);
  t.coverage = coverage.is_null() ? std::numeric_limits<double>::quiet_NaN() : number("coverage");
  t.empty_space_probes = count("empty_space_probes");
  t.empty_space_violations = count("empty_space_violations");
  t.empty_space_violation_mean = number("empty_space_violation_mean");
  // Written since the sensor metric; earlier files have neither.
  if (j.contains("unseen_points")) t.unseen_points = count("unseen_points");
  if (j.contains("seen_through_points")) t.seen_through_points = count("seen_through_points");
  if (j.contains("empty_space_observed") && !j["empty_space_observed"].is_null())
    t.empty_space_observed = number("empty_space_observed");
  // Written since threshold_range; earlier files were never scaled.
  if (j.contains("range_scale")) {
    t.range_scale = number("range_scale");
    if (!(t.range_scale > 0.0 && t.range_scale <= 1.0))
      throw Error(where + ".range_scale: must be in (0, 1]");
  }
  if (j.contains("colour_points")) {  // written since the colour term, where it was measured
    t.colour_difference = number("colour_difference");
    t.colour_points = count("colour_points");
    t.colour_penalty = number("colour_penalty");
    if (!(t.colour_penalty >= 0.0)) throw Error(where + ".colour_penalty: must be non-negative");
  }
  t.finish();
  return t;
}

}  // namespace lmk::detail
