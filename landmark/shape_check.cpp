// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/shape_check.h"

#include <cmath>
#include <cstdio>

#include "lmk/geometry/frame_noise.h"
#include "lmk/geometry/range_image.h"

namespace lmk {

namespace {

constexpr double kSymmetryTurn = 1.0;  ///< rad

double capture_range(const Landmark& landmark) {
  return (landmark.box.center() - landmark.sensor_origin).norm();
}

// The slide check's findings: the freest motion that is no symmetry, and the symmetry axes (turns
// free through a radian and more: an axis of revolution, where the normals' own noise
// and a faceted surface keep the extent finite; a shape that is no symmetry turns a few degrees).
void record_slides(const SlideReport& report, CaptureFindings& f) {
  for (const Slide& s : report.slides) {
    if (s.turn && !(s.extent < kSymmetryTurn)) {
      if (f.symmetry_axes.empty()) f.symmetry_centre = s.through;
      f.symmetry_axes.push_back(s.axis);
      continue;
    }
    if (s.displacement > f.slide) {
      f.slide = s.displacement;
      f.slide_axis = s.axis;
      f.slide_turn = s.turn;
    }
  }
}

}  // namespace

ShapeCheck check_shape(const Landmark& landmark, const PointCloud* scene,
                       const SceneSettings& scene_settings) {
  ShapeCheck check;
  CaptureFindings& f = check.findings;
  f.present = true;
  if (scene) {
    if (const std::optional<RangeImage> image = RangeImage::from_cloud(*scene)) {
      const MeasuredNoise noise = measure_noise_at(*image, landmark.box.center().cast<float>());
      if (noise.measured()) f.noise = noise.sigma;
    }
  }
  if (landmark.settings.allow_flat) return check;
  // The residual between two measurements of the same surface, each with the capture's noise.
  const DepthNoise model = scene_settings.depth_noise();
  const double m = model.measurement_sigma_or(f.noise, capture_range(landmark));
  check.slides = slide_check(landmark.points, model.residual_of(m, m));
  record_slides(check.slides, f);
  return check;
}

std::optional<Symmetry> capture_symmetry(const Landmark& landmark) {
  const CaptureFindings& f = landmark.findings;
  if (!f.present || f.symmetry_axes.empty()) return std::nullopt;
  const Eigen::Isometry3d box_from_capture = landmark.box.pose.inverse();
  Symmetry s;
  s.axis = (box_from_capture.linear() * f.symmetry_axes.front()).normalized();
  s.order = 0;
  s.centre = box_from_capture * f.symmetry_centre;
  return s;
}

bool CaptureFindings::warned() const {
  return slide > 0.0 || (look_alike_checked && (look_alikes > 0 || !found_itself));
}

std::vector<std::string> CaptureFindings::warnings() const {
  std::vector<std::string> lines;
  char text[160];
  if (slide > 0.0) {
    // A turn's extent is how far it moves the points: the same yardstick as a slide's.
    const char* how = slide_turn ? "turns about" : "slides along";
    if (std::isinf(slide)) {
      std::snprintf(text, sizeof(text), "%s (%.2f, %.2f, %.2f) freely within the noise", how,
                    slide_axis.x(), slide_axis.y(), slide_axis.z());
    } else {
      std::snprintf(text, sizeof(text),
                    "%s (%.2f, %.2f, %.2f), moving its points %.0f cm within "
                    "the noise",
                    how, slide_axis.x(), slide_axis.y(), slide_axis.z(), slide * 100.0);
    }
    lines.push_back(text);
  }
  if (look_alike_checked && !found_itself) lines.push_back("not found in its own capture scene");
  if (look_alike_checked && look_alikes > 0) {
    std::snprintf(text, sizeof(text), "matches %zu other place%s in its capture scene", look_alikes,
                  look_alikes == 1 ? "" : "s");
    lines.push_back(text);
  }
  return lines;
}

}  // namespace lmk
