// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The JSON form of a match's confidence (match_confidence.h), shared by `lmk find --json`,
// `lmk serve`, the evaluation's cache and reports, Python and ROS:
//   {"probability", "features": {name: value}, "margin", "local_margin", "elsewhere_margin",
//   "error_sigma", "fit", "range", "model_noise", "measured_noise", "scene_noise",
//   "scene_noise_measured", "capture_noise",
//    "landmark_size", "landmark_points", "seen_fraction", "capture_range", "view_change",
//    "capture": null | {capture findings},
//    "support", "freedom", "freest": {"turn", "axis"}, "coverage", "intrusion",
//    "free_space_seen", "free_space_unconfirmed", "doubt",
//    "competitor": null | {"kind", "position", "orientation", "error", "distance", "angle"}}
// Numbers that are not finite (no probability, no rival: an infinite margin) are null.
// Header-only; internal/: shared within lmk, not installed.

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "lmk/geometry/error.h"
#include "lmk/geometry/settings_schema.h"
#include "lmk/json/box_json.h"
#include "lmk/json/pose_json.h"
#include "lmk/landmark/internal/capture_findings_json.h"
#include "lmk/search/confidence/confidence_calibration.h"
#include "lmk/search/confidence/match_confidence.h"

namespace lmk::detail {

/// `object[key]` as a number, `if_null` where it is null; lmk::Error, starting with `at`, for
/// anything else or a missing key.
inline double number_or(const nlohmann::json& object, const char* key, double if_null,
                        const std::string& at) {
  const nlohmann::json& v = json_field(object, key, at);
  if (v.is_null()) return if_null;
  if (!v.is_number()) throw Error(at + "." + key + ": must be a number or null");
  return v.get<double>();
}

inline nlohmann::json confidence_to_json(const MatchConfidence& c) {
  nlohmann::json competitor = nullptr;
  if (c.competitor.kind != Competitor::Kind::none) {
    competitor = box_to_json(c.competitor.box);
    competitor["kind"] = setting_name(c.competitor.kind);
    competitor["error"] = finite_or_null(c.competitor.error);
    competitor["distance"] = c.competitor.distance;
    competitor["angle"] = c.competitor.angle;
  }
  // The calibration's inputs as it computes them (confidence_calibration.h), so that
  // lmk calibrate-confidence fits on exactly what the search will weigh.
  nlohmann::json features = nlohmann::json::object();
  const std::vector<double> values = confidence_features(c);
  for (std::size_t k = 0; k < values.size(); ++k) {
    features[confidence_feature_names()[k]] = values[k];
  }
  return {{"probability", finite_or_null(c.probability)},
          {"features", features},
          {"margin", finite_or_null(c.margin)},
          {"local_margin", finite_or_null(c.local_margin)},
          {"elsewhere_margin", finite_or_null(c.elsewhere_margin)},
          {"error_sigma", finite_or_null(c.error_sigma)},
          {"fit", finite_or_null(c.fit)},
          {"range", finite_or_null(c.range)},
          {"model_noise", finite_or_null(c.model_noise)},
          {"measured_noise", finite_or_null(c.measured_noise)},
          {"scene_noise", finite_or_null(c.scene_noise)},
          {"scene_noise_measured", c.scene_noise_measured},
          {"capture_noise", finite_or_null(c.capture_noise)},
          {"landmark_size", finite_or_null(c.landmark_size)},
          {"landmark_points", c.landmark_points},
          {"seen_fraction", finite_or_null(c.seen_fraction)},
          {"capture_range", finite_or_null(c.capture_range)},
          {"view_change", finite_or_null(c.view_change)},
          {"capture", c.capture.present ? capture_findings_to_json(c.capture) : nullptr},
          {"support", c.support},
          {"freedom", finite_or_null(c.freedom)},
          {"freest", {{"turn", c.freest.turn}, {"axis", vector_to_json(c.freest.axis)}}},
          {"coverage", finite_or_null(c.coverage)},
          {"intrusion", c.intrusion},
          {"free_space_seen", finite_or_null(c.free_space_seen)},
          {"free_space_unconfirmed", c.free_space_unconfirmed},
          {"doubt", c.doubt},
          {"competitor", competitor}};
}

/// The evidence of issue #59 in confidence_to_json's form into `c`: the noise, measured and
/// modelled, the landmark's own figures and its capture findings.
inline void landmark_evidence_from_json(const nlohmann::json& j, const std::string& where,
                                        MatchConfidence& c) {
  const auto number = [&](const char* key) {
    return number_or(j, key, std::numeric_limits<double>::quiet_NaN(), where);
  };
  c.model_noise = number("model_noise");
  c.measured_noise = number("measured_noise");
  c.scene_noise = number("scene_noise");
  c.capture_noise = number("capture_noise");
  c.landmark_size = number("landmark_size");
  c.seen_fraction = number("seen_fraction");
  c.capture_range = number("capture_range");
  c.view_change = number("view_change");
  const nlohmann::json& measured = json_field(j, "scene_noise_measured", where);
  if (!measured.is_boolean()) throw Error(where + ".scene_noise_measured: must be true or false");
  c.scene_noise_measured = measured.get<bool>();
  const nlohmann::json& points = json_field(j, "landmark_points", where);
  if (!points.is_number_unsigned()) throw Error(where + ".landmark_points: must be a count");
  c.landmark_points = points.get<std::size_t>();
  const nlohmann::json& capture = json_field(j, "capture", where);
  if (!capture.is_null()) c.capture = capture_findings_from_json(capture, where + ".capture");
}

/// The inverse of confidence_to_json. A null margin reads back as +infinity (no rival), a null
/// freedom as +infinity only when the support had points (a pose free along some direction), other
/// nulls as NaN.
inline MatchConfidence confidence_from_json(const nlohmann::json& j, const std::string& where) {
  const auto number = [&](const char* key, double if_null) {
    return number_or(j, key, if_null, where);
  };
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  MatchConfidence c;
  c.probability = number("probability", nan);
  c.margin = number("margin", inf);
  c.local_margin = number("local_margin", inf);
  c.elsewhere_margin = number("elsewhere_margin", inf);
  c.error_sigma = number("error_sigma", nan);
  c.fit = number("fit", nan);
  c.range = number("range", nan);
  // Absent before search revision 8: the model's noise, nothing known of the landmark.
  if (j.contains("scene_noise")) landmark_evidence_from_json(j, where, c);
  const nlohmann::json& support = json_field(j, "support", where);
  if (!support.is_number_unsigned()) throw Error(where + ".support: must be a count");
  c.support = support.get<std::size_t>();
  c.freedom = number("freedom", c.support >= 6 ? inf : nan);
  const std::string freest_at = where + ".freest";
  const nlohmann::json& freest = json_field(j, "freest", where);
  const nlohmann::json& turn = json_field(freest, "turn", freest_at);
  if (!turn.is_boolean()) throw Error(freest_at + ".turn: must be true or false");
  c.freest.turn = turn.get<bool>();
  c.freest.axis = numbers_from_json(json_field(freest, "axis", freest_at), 3, freest_at + ".axis");
  c.freest.displacement = c.freedom;
  c.coverage = number("coverage", nan);
  c.intrusion = number("intrusion", nan);
  if (!(c.intrusion >= 0.0 && c.intrusion <= 1.0))
    throw Error(where + ".intrusion: must be in [0, 1]");
  // Absent before search revision 7: not measured.
  if (j.contains("free_space_seen")) c.free_space_seen = number("free_space_seen", nan);
  if (j.contains("free_space_unconfirmed")) {
    const nlohmann::json& unconfirmed = j["free_space_unconfirmed"];
    if (!unconfirmed.is_boolean())
      throw Error(where + ".free_space_unconfirmed: must be true or false");
    c.free_space_unconfirmed = unconfirmed.get<bool>();
  }
  const nlohmann::json& doubt = json_field(j, "doubt", where);
  if (!doubt.is_string()) throw Error(where + ".doubt: must be a string");
  c.doubt = doubt.get<std::string>();
  const nlohmann::json& competitor = json_field(j, "competitor", where);
  if (!competitor.is_null()) {
    const std::string at = where + ".competitor";
    const nlohmann::json& kind = json_field(competitor, "kind", at);
    const std::optional<Competitor::Kind> named =
        kind.is_string() ? setting_value_named<Competitor::Kind>(kind.get<std::string>())
                         : std::nullopt;
    if (!named || *named == Competitor::Kind::none)
      throw Error(at + ".kind: must be \"slide\", \"turn\" or \"look-alike\"");
    c.competitor.kind = *named;
    c.competitor.box = box_from_json(competitor, at);
    c.competitor.error = number_or(competitor, "error", inf, at);
    c.competitor.distance = number_or(competitor, "distance", nan, at);
    c.competitor.angle = number_or(competitor, "angle", nan, at);
  }
  return c;
}

}  // namespace lmk::detail
