// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The depth cameras the generator renders with (issue #59): a confidence calibrated on one sensor's
// scenes says nothing of another's, so the benchmark renders the same worlds with three kinds of
// camera, each from the ranges it works at:
// - `kinect`: structured light (Kinect v1), 640x480 at 525 px, 0.5-4 m, axial noise
//   sigma(z) = 0.0013 z^2, disparity levels of 1/8 px;
// - `realsense`: active stereo (D415/D435-like), 640x480 at 615 px, 0.2-3 m, sigma(z) =
//   0.0035 z^2, levels of 1/32 px;
// - `tof`: time of flight (Kinect v2-like), 512x424 at 365 px, 0.5-4.5 m, sigma(z) = 0.001 +
//   0.0005 z^2, no levels.
//
// The Kinect's is DepthSensorSettings' default, fitted to 51 real frames (`lmk sensor-check`). The
// RealSense's noise is the one measured in the real desk sequence of ../shared/data/real (the
// sequence tuned on: 0.55 mm at 0.4 m, 3.5 mm at 1 m; geometry/frame_noise.h), its levels a
// 50 mm baseline's at 1/32 px. The time-of-flight camera has no disparity and so no levels and no
// projector shadow, but mixes the returns of both sides of an edge far more often.

#include <string>
#include <vector>

#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/instance_visibility.h"

namespace lmk {

struct SensorModel {
  std::string name;
  DepthSensorSettings settings;  ///< noise on, seed 0: the caller sets both
  /// Where the benchmark places this camera: its distance to what it looks at, m (a
  /// ViewpointRange's, with the default azimuth and heights). A landmark is demonstrated from its
  /// scene's own camera, moved along its line of sight into this range.
  double min_range = 0.7, max_range = 3.0;
};

/// "kinect", "realsense", "tof".
const std::vector<std::string>& sensor_model_names();

/// The model called `name`; lmk::Error naming the known ones otherwise.
const SensorModel& sensor_model(const std::string& name);

}  // namespace lmk
