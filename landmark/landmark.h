#pragma once
// The custom landmark of Huang & Cakmak: l = (P, B), the points a user cut out of a scene with a
// box, and the box itself. The box's empty margins say where space must stay free.

#include <cstdint>
#include <string>

#include "geometry/box.h"
#include "geometry/point_cloud.h"

namespace lmk {

/// Version of the landmark model and of its .lmk file; bumped whenever either changes.
inline constexpr int kLandmarkFormatVersion = 1;

struct CaptureSettings {
  double leaf_size = 0.005;     ///< voxel leaf of the captured points, m (the paper's 5 mm)
  std::size_t min_points = 30;  ///< fewer points than this after downsampling is an error
  double max_box_side = 3.0;    ///< a box side longer than this is an error, m
};

struct Landmark {
  std::string name;
  /// The captured points, in the capture (scene) frame, downsampled to settings.leaf_size.
  PointCloud points;
  /// The box the user drew, in the capture frame (T_capture_box at its centre).
  Box box;
  /// Where the sensor was at capture, in the capture frame: space between it and the surface was
  /// observed free.
  Eigen::Vector3d sensor_origin = Eigen::Vector3d::Zero();
  CaptureSettings settings;
  int format_version = kLandmarkFormatVersion;

  /// Throws lmk::Error naming the first field that is wrong (used after loading and importing).
  void validate(const std::string& what) const;
};

/// Cuts a landmark out of `scene`: the finite scene points inside the oriented `box` (given in the
/// scene frame), voxel-downsampled to settings.leaf_size. Throws lmk::Error for an empty name, a
/// box with a non-positive, non-finite or oversized side, a box with no scene point inside, or too
/// few points.
Landmark capture(const PointCloud& scene, const Box& box, const std::string& name,
                 const CaptureSettings& settings = {});

}  // namespace lmk
