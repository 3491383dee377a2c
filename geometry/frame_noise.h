// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The depth noise of a frame, measured in the frame itself (issue #59): the spread of its own
// planar surfaces about their planes (plane_patches.h), at the range asked about, near the place
// asked about. A confidence scaled by it means the same on a Kinect at 2.5 m as on a RealSense at
// 0.4 m, where a sensor model's coefficient is right for one camera only
// (docs/evaluation.md, "A confidence that transfers").
//
// Depth cameras' noise grows with the square of the depth (a structured-light or stereo camera's
// disparity error, and its quantisation), so a patch's spread is carried to the range asked about
// by (z / z_patch)^2; only patches within kNoiseDepthBand of that range are used, so the scaling
// moves them little whatever the camera.

#include <Eigen/Core>
#include <cstddef>
#include <limits>

#include "lmk/geometry/plane_patches.h"
#include "lmk/geometry/range_image.h"

namespace lmk {

/// Patches whose depth lies within this fraction of the range asked about are at that range.
inline constexpr double kNoiseDepthBand = 0.25;
/// The fewest patches a measurement is made of: fewer say too little (a frame of one wall seen
/// edge-on, a tiny crop) and the caller falls back on a sensor model.
inline constexpr std::size_t kMinNoisePatches = 6;

/// The patches the noise is measured on: plane_patches.h's tiles, with a third of their pixels
/// enough. Depth registered to a larger colour image leaves whole rows and columns empty in a
/// regular pattern (the RealSense desk of ../shared/data/real: a third of the pixels), and the
/// points left still sample the plane.
inline PlanePatchSettings noise_patch_settings() {
  PlanePatchSettings s;
  s.min_fill = 0.3;
  return s;
}

/// Patches seen more obliquely than this (radians between normal and ray) are not measured on.
inline constexpr double kMaxNoiseIncidence = 60.0 * 3.14159265358979323846 / 180.0;

/// A measurement of one depth measurement's noise along its ray (the axial noise
/// DepthNoise::measurement_sigma models): a patch's spread about its plane over the cosine between
/// the plane's normal and the ray.
struct MeasuredNoise {
  double sigma = std::numeric_limits<double>::quiet_NaN();  ///< m; NaN: not measured
  std::size_t patches = 0;  ///< planar patches at the range it was measured on
  double window = 0.0;      ///< half the side of the image window searched, pixels
  bool measured() const { return patches >= kMinNoisePatches; }
};

/// The noise of `image` at depth `depth` (m) near pixel `pixel` (u right, v down): the median
/// spread of the planar patches within kNoiseDepthBand of that depth, scaled to it, in a window
/// around the pixel that starts at `min_window` pixels a side's half and doubles until it holds
/// kMinNoisePatches such patches or the whole image. Unmeasured (sigma NaN) for an unorganised
/// image, where the projected points of a cloud are no pixels' neighbours, and where too few
/// patches lie at that depth anywhere.
MeasuredNoise measure_noise_near(const RangeImage& image, const Eigen::Vector2d& pixel,
                                 double depth, double min_window = 48.0,
                                 const PlanePatchSettings& patches = noise_patch_settings());

/// The same around where `point` (the image's cloud frame) projects, at its depth.
MeasuredNoise measure_noise_at(const RangeImage& image, const Eigen::Vector3f& point,
                               double min_window = 48.0);

}  // namespace lmk
