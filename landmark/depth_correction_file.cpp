// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/depth_correction_file.h"

#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/input_file.h"
#include "lmk/json/depth_correction_json.h"

namespace lmk {
namespace {
constexpr const char* kFormat = "lmk-depth-correction";
}  // namespace

DepthCalibration load_depth_correction(const std::string& path) {
  const detail::JsonReader r(path);
  const nlohmann::json j = r.parse(read_input_file(path, kJsonInput));
  if (!j.is_object()) r.fail("", "must be a JSON object");
  if (!j.contains("format") || j["format"] != kFormat) {
    r.fail("format", "is " + (j.contains("format") ? j["format"].dump() : std::string("missing")) +
                         ", not \"" + kFormat + "\"");
  }
  r.require_version(j, kDepthCorrectionFormatVersion, "depth correction");
  return detail::depth_calibration_from_json(j, r);
}

std::optional<DepthCorrection> load_depth_correction_if_given(const std::string& path) {
  if (path.empty()) return std::nullopt;
  return load_depth_correction(path).correction;
}

void save_depth_correction(const std::string& path, const DepthCalibration& calibration) {
  calibration.correction.validate();
  nlohmann::json j = {{"format", kFormat}, {"version", kDepthCorrectionFormatVersion}};
  j.update(detail::depth_calibration_to_json(calibration));
  write_text_atomically(path, j.dump(1) + "\n");
}

void correct_depth(PointCloud& frame, const std::string& path) {
  if (path.empty()) return;
  const DepthCalibration calibration = load_depth_correction(path);
  try {
    calibration.correction.apply(frame);
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
}

}  // namespace lmk
