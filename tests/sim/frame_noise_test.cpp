// SPDX-License-Identifier: BSD-3-Clause
// The noise measured in a frame itself (geometry/frame_noise.h, issue #59): on walls the simulated
// Kinect renders, it is the generator's own noise at their range.

#include "lmk/geometry/frame_noise.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lmk/geometry/depth_noise.h"
#include "lmk/geometry/pose.h"
#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/mesh.h"
#include "lmk/sim/sensor_models.h"

namespace lmk {
namespace {

// A wall filling the image `z` m away, turned `yaw` radians from facing the sensor, rendered with
// `sensor`'s noise.
RangeImage wall_at(double z, double yaw, std::uint64_t seed,
                   DepthSensorSettings sensor = DepthSensorSettings()) {
  sensor.seed = seed;
  TriangleMesh wall;
  wall.append(make_box_mesh({4.0 * z, 4.0 * z, 0.01}), pose_from_xyz_rpy({0, 0, z}, {0, yaw, 0}));
  const PointCloud frame = render_depth(wall, Eigen::Isometry3d::Identity(), sensor);
  std::optional<RangeImage> image = RangeImage::from_cloud(frame);
  if (!image) throw std::runtime_error("the wall's frame has no range image");
  return *image;
}

// What the generator puts into one measurement at depth z: its Gaussian axial noise, the
// disparity's levels (uniform rounding: spacing / sqrt(12)) and the driver's millimetres.
double generator_sigma(double z, const DepthSensorSettings& s = DepthSensorSettings()) {
  const double axial = s.noise_a + s.noise_b * (z - s.noise_z0) * (z - s.noise_z0);
  const double levels = depth_level_spacing(z, s);
  return std::sqrt(axial * axial + (levels * levels + s.depth_unit * s.depth_unit) / 12.0);
}

TEST(FrameNoise, AFlatWallsNoiseIsTheGeneratorsAtTwoRanges) {
  // The Kinect's generator noise is DepthNoise's model (lmk sensor-check's fit).
  EXPECT_NEAR(generator_sigma(2.0),
              std::hypot(DepthNoise{}.measurement_sigma(2.0), 0.001 / std::sqrt(12.0)), 1e-9);
  for (const std::string& name : sensor_model_names()) {
    const SensorModel& model = sensor_model(name);
    // Two ranges each camera works at: near and far in the benchmark's own range for it.
    for (const double z : {model.min_range + 0.1, model.max_range - 0.2}) {
      const RangeImage image = wall_at(z, 0.35, 5, model.settings);
      const PinholeIntrinsics& k = image.intrinsics();
      // Measured at the image's centre, where the wall lies at depth z.
      const MeasuredNoise noise = measure_noise_near(image, {k.cx, k.cy}, z);
      ASSERT_TRUE(noise.measured()) << name << " at " << z << " m: " << noise.patches << " patches";
      EXPECT_NEAR(noise.sigma / generator_sigma(z, model.settings), 1.0, 0.2)
          << name << " at " << z << " m: measured " << noise.sigma << ", generator "
          << generator_sigma(z, model.settings);
    }
  }
}

TEST(FrameNoise, GrowsWithRangeAsTheSensorsDoes) {
  const double near = measure_noise_near(wall_at(1.0, 0.35, 7), {319.5, 239.5}, 1.0).sigma;
  const double far = measure_noise_near(wall_at(2.5, 0.35, 7), {319.5, 239.5}, 2.5).sigma;
  EXPECT_GT(far / near, 0.6 * 6.25) << near << " at 1 m, " << far << " at 2.5 m";
}

// Nothing at the range asked about, and no organised pixels: no measurement, so the caller falls
// back on its sensor model instead of trusting a number from elsewhere.
TEST(FrameNoise, NothingAtTheRangeAskedAboutIsNotMeasured) {
  const RangeImage image = wall_at(1.0, 0.35, 3);
  const MeasuredNoise far = measure_noise_near(image, {319.5, 239.5}, 3.0);
  EXPECT_FALSE(far.measured());
  EXPECT_TRUE(std::isnan(far.sigma));

  PointCloud scattered;
  for (int i = 0; i < 1000; ++i) scattered.points.emplace_back(0.001f * i, 0.0f, 1.0f);
  scattered.set_unorganized();
  const std::optional<RangeImage> projected = RangeImage::from_cloud(scattered);
  ASSERT_TRUE(projected);
  EXPECT_FALSE(measure_noise_near(*projected, {319.5, 239.5}, 1.0).measured());
}

}  // namespace
}  // namespace lmk
