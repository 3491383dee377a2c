// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/sim/sensor_models.h"

#include "lmk/geometry/error.h"

namespace lmk {

namespace {

SensorModel kinect() {
  SensorModel m;
  m.name = "kinect";
  m.min_range = 0.7;
  m.max_range = 3.0;
  return m;  // DepthSensorSettings' defaults are the Kinect v1's
}

SensorModel realsense() {
  SensorModel m;
  m.name = "realsense";
  DepthSensorSettings& s = m.settings;
  s.fx = s.fy = 615.0;
  s.cx = 319.5;
  s.cy = 239.5;
  s.min_range = 0.2;
  s.max_range = 3.0;
  s.noise_b = 0.0035;
  s.baseline = 0.05;
  s.disparity_focal = 615.0;
  s.disparity_step = 1.0 / 32.0;
  s.flying_pixel_rate = 0.03;
  m.min_range = 0.4;
  m.max_range = 1.5;
  return m;
}

SensorModel time_of_flight() {
  SensorModel m;
  m.name = "tof";
  DepthSensorSettings& s = m.settings;
  s.width = 512;
  s.height = 424;
  s.fx = s.fy = 365.0;
  s.cx = 255.5;
  s.cy = 211.5;
  s.min_range = 0.5;
  s.max_range = 4.5;
  s.noise_a = 0.001;
  s.noise_b = 0.0005;
  s.disparity_step = 0.0;  // no disparity: depth from the phase of the returned light
  s.shadows = false;
  s.flying_pixel_rate = 0.1;
  m.min_range = 0.6;
  m.max_range = 3.0;
  return m;
}

// Every model, in the order sensor_model_names() gives: a new camera is one function and one
// entry here.
const std::vector<SensorModel>& sensor_models() {
  static const std::vector<SensorModel> models = {kinect(), realsense(), time_of_flight()};
  return models;
}

}  // namespace

const std::vector<std::string>& sensor_model_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const SensorModel& m : sensor_models()) out.push_back(m.name);
    return out;
  }();
  return names;
}

const SensorModel& sensor_model(const std::string& name) {
  for (const SensorModel& m : sensor_models()) {
    if (m.name == name) return m;
  }
  std::string known;
  for (const std::string& n : sensor_model_names()) known += (known.empty() ? "" : ", ") + n;
  throw Error("unknown sensor model '" + name + "' (known: " + known + ")");
}

}  // namespace lmk
