// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The JSON form of what the capture check found (capture_findings.h), as a .lmk file stores it (the
// metadata lmk_capture_findings), `lmk landmark export` writes it, and a match's confidence carries
// it:
//   {"noise", "slide", "slide_axis", "slide_turn", "symmetry_axes": [[x, y, z], ...],
//    "symmetry_centre", "look_alike_checked", "found_itself", "look_alikes", "look_alike_ratio",
//    "warnings": [...]}
// Numbers that are not finite (no noise measured, no look-alike, a free slide) are null; "warnings"
// is written for people and ignored on reading. Header-only; internal/: not installed.

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "lmk/geometry/error.h"
#include "lmk/json/pose_json.h"
#include "lmk/landmark/capture_findings.h"

namespace lmk::detail {

/// The most symmetry axes a landmark has (a ball's three).
inline constexpr std::size_t kMaxSymmetryAxes = 3;

inline nlohmann::json capture_findings_to_json(const CaptureFindings& f) {
  nlohmann::json axes = nlohmann::json::array();
  for (const Eigen::Vector3d& a : f.symmetry_axes) axes.push_back(vector_to_json(a));
  return {{"noise", finite_or_null(f.noise)},
          {"slide", finite_or_null(f.slide)},
          {"slide_axis", vector_to_json(f.slide_axis)},
          {"slide_turn", f.slide_turn},
          {"symmetry_axes", axes},
          {"symmetry_centre", vector_to_json(f.symmetry_centre)},
          {"look_alike_checked", f.look_alike_checked},
          {"found_itself", f.found_itself},
          {"look_alikes", f.look_alikes},
          {"look_alike_ratio", finite_or_null(f.look_alike_ratio)},
          {"warnings", f.warnings()}};
}

/// The inverse of capture_findings_to_json. Throws lmk::Error, starting with `where`, for anything
/// else: a field missing or of the wrong type, a negative or NaN number, an axis that is not a unit
/// vector, more than kMaxSymmetryAxes axes. A null slide reads back as free (+infinity), a null
/// noise as not measured, a null ratio as no look-alike.
inline CaptureFindings capture_findings_from_json(const nlohmann::json& j,
                                                  const std::string& where) {
  if (!j.is_object()) throw Error(where + ": must be a JSON object");
  const auto number = [&](const char* key, double if_null) {
    const nlohmann::json& v = json_field(j, key, where);
    if (v.is_null()) return if_null;
    if (!v.is_number() || !(v.get<double>() >= 0.0) || !std::isfinite(v.get<double>()))
      throw Error(where + "." + key + ": must be a non-negative number or null");
    return v.get<double>();
  };
  const auto flag = [&](const char* key) {
    const nlohmann::json& v = json_field(j, key, where);
    if (!v.is_boolean()) throw Error(where + "." + key + ": must be true or false");
    return v.get<bool>();
  };
  const auto unit = [&](const nlohmann::json& v, const std::string& at, bool zero_allowed) {
    const Eigen::Vector3d a = numbers_from_json(v, 3, at);
    const double norm = a.norm();
    if (!(std::abs(norm - 1.0) < 1e-3) && !(zero_allowed && norm == 0.0))
      throw Error(at + ": must be a unit vector");
    return a;
  };
  const double inf = std::numeric_limits<double>::infinity();
  CaptureFindings f;
  f.present = true;
  f.noise = number("noise", std::numeric_limits<double>::quiet_NaN());
  f.slide = number("slide", inf);
  f.slide_axis = unit(json_field(j, "slide_axis", where), where + ".slide_axis", true);
  f.slide_turn = flag("slide_turn");
  const nlohmann::json& axes = json_field(j, "symmetry_axes", where);
  if (!axes.is_array() || axes.size() > kMaxSymmetryAxes)
    throw Error(where + ".symmetry_axes: must be an array of at most 3 axes");
  for (std::size_t k = 0; k < axes.size(); ++k)
    f.symmetry_axes.push_back(
        unit(axes[k], where + ".symmetry_axes[" + std::to_string(k) + "]", false));
  f.symmetry_centre =
      numbers_from_json(json_field(j, "symmetry_centre", where), 3, where + ".symmetry_centre");
  if (!f.symmetry_centre.allFinite()) throw Error(where + ".symmetry_centre: must be finite");
  f.look_alike_checked = flag("look_alike_checked");
  f.found_itself = flag("found_itself");
  const nlohmann::json& count = json_field(j, "look_alikes", where);
  if (!count.is_number_unsigned()) throw Error(where + ".look_alikes: must be a count");
  f.look_alikes = count.get<std::size_t>();
  f.look_alike_ratio = number("look_alike_ratio", inf);
  return f;
}

}  // namespace lmk::detail
