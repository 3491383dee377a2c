// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A depth camera's fixed depth error, undone (issue #33). A real Kinect v1 reads depth a little too
// far, more so the farther and the nearer the image's edge: on the kitchen sequence of
// ../shared/data/real a landmark cut from one frame fitted another 3 degrees askew until the frames
// were corrected (docs/evaluation.md, "Calibrating the Kinect's depth"). The model is
// z' = z + D z^2 with D constant over each cell of a grid over the image;
// datasets/depth_calibration.h fits it from a sequence with camera poses,
// landmark/depth_correction_file.h stores it, and a capture or a search applies it to each raw
// frame before anything else reads it.

#include <cstddef>
#include <string>
#include <vector>

#include "lmk/geometry/point_cloud.h"

namespace lmk {

struct DepthCorrection {
  int cols = 1, rows = 1;         ///< cells across and down the image
  int width = 640, height = 480;  ///< the image the cells divide, pixels
  std::vector<double> per_metre;  ///< D of each cell, row-major, 1/m: z' = z + D z^2

  /// The cell of pixel (u, v), row-major.
  int cell(int u, int v) const;
  /// D at pixel (u, v).
  double at(int u, int v) const;
  /// Moves each finite point of an organised width x height frame along its ray from the sensor
  /// (frame.T_cloud_sensor: the correction works in the sensor's optical frame, z forward) to its
  /// corrected depth. lmk::Error, naming both sizes, for a frame of another size or an unorganised
  /// one: only the pixel says which cell's error a point carries.
  void apply(PointCloud& frame) const;
  /// lmk::Error naming the first inconsistency: a grid that does not divide the image, a D per
  /// cell missing, a D that is not finite or beyond +-kMaxDepthCorrection.
  void validate() const;
};

/// The largest |D| accepted, 1/m: 5% of the depth per metre of it (a Kinect v1's is under 2%).
inline constexpr double kMaxDepthCorrection = 0.05;

/// A fitted correction with what the fit saw.
struct DepthCalibration {
  DepthCorrection correction;
  std::size_t correspondences = 0;
  double rms_before = 0.0, rms_after = 0.0;  ///< m, over the correspondences of the fit
  std::string source;                        ///< what it was fitted on, for the record
};

}  // namespace lmk
