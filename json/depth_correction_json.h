// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The JSON form of a fitted depth correction (geometry/depth_correction.h), shared by the
// correction file (landmark/depth_correction_file.h) and the record of an RGB-D import
// (import.json's "depth_correction"). Header-only and internal, like pose_json.h.

#include <nlohmann/json.hpp>

#include "lmk/geometry/depth_correction.h"
#include "lmk/json/json_reader.h"

namespace lmk::detail {

inline constexpr const char* kDepthCorrectionModel = "z' = z + D z^2, D per cell (1/m), row-major";

inline nlohmann::json depth_calibration_to_json(const DepthCalibration& c) {
  nlohmann::json j = {{"model", kDepthCorrectionModel},
                      {"image", {c.correction.width, c.correction.height}},
                      {"cells", {c.correction.cols, c.correction.rows}},
                      {"per_metre", c.correction.per_metre},
                      {"correspondences", c.correspondences},
                      {"rms_before_m", c.rms_before},
                      {"rms_after_m", c.rms_after}};
  if (!c.source.empty()) j["source"] = c.source;
  return j;
}

/// The form depth_calibration_to_json writes, checked field by field (lmk::Error naming the file
/// and the field) and validated (DepthCorrection::validate).
inline DepthCalibration depth_calibration_from_json(const nlohmann::json& j,
                                                    const JsonReader& reader) {
  const auto whole_pair = [&](const char* key) {
    const nlohmann::json& v = reader.field(j, "", key);
    if (!v.is_array() || v.size() != 2 || !v[0].is_number_integer() || !v[1].is_number_integer()) {
      reader.fail(key, "must be two whole numbers, not " + v.dump());
    }
    return std::pair<int, int>(v[0].get<int>(), v[1].get<int>());
  };
  DepthCalibration c;
  std::tie(c.correction.width, c.correction.height) = whole_pair("image");
  std::tie(c.correction.cols, c.correction.rows) = whole_pair("cells");
  const nlohmann::json& d = reader.field(j, "", "per_metre");
  if (!d.is_array()) reader.fail("per_metre", "must be an array of numbers");
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (!d[i].is_number()) reader.fail(at("", "per_metre", i), "must be a number");
    c.correction.per_metre.push_back(d[i].get<double>());
  }
  try {
    c.correction.validate();
  } catch (const Error& e) {
    reader.fail("", e.what());
  }
  if (j.contains("correspondences") && j["correspondences"].is_number_unsigned())
    c.correspondences = j["correspondences"].get<std::size_t>();
  if (j.contains("rms_before_m") && j["rms_before_m"].is_number())
    c.rms_before = j["rms_before_m"].get<double>();
  if (j.contains("rms_after_m") && j["rms_after_m"].is_number())
    c.rms_after = j["rms_after_m"].get<double>();
  if (j.contains("source") && j["source"].is_string()) c.source = j["source"].get<std::string>();
  return c;
}

}  // namespace lmk::detail
