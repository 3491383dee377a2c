// SPDX-License-Identifier: BSD-3-Clause
// The depth calibration finds a depth error planted in rendered frames whose poses are known, and
// its correction puts the frames back together.
#include "lmk/datasets/depth_calibration.h"

#include <gtest/gtest.h>

#include "lmk/geometry/error.h"
#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/tabletop_scene.h"

namespace lmk {
namespace {

constexpr double kPlanted = 0.01;  // 1/m: the frames read z + 0.01 z^2 (1.4 cm too far at 1.2 m)

struct Frames {
  std::vector<PointCloud> clouds;  // camera frame, with the planted error
  std::vector<Eigen::Isometry3d> poses;
  PinholeIntrinsics intrinsics;
};

// The tabletop seen from a sensor backing away 4 cm and turning 1 degree a frame, so that the
// same surface lies at other depths in other frames and a depth error shows.
Frames rendered_frames() {
  const SyntheticScene scene = make_tabletop_scene(1);
  DepthSensorSettings sensor;
  sensor.noise = false;
  Frames f;
  f.intrinsics = {sensor.fx, sensor.fy, sensor.cx, sensor.cy, sensor.width, sensor.height};
  for (int i = 0; i < 8; ++i) {
    const Eigen::Isometry3d T = scene.T_world_sensor * Eigen::Translation3d(0.0, 0.0, -0.04 * i) *
                                Eigen::AngleAxisd(0.0175 * i, Eigen::Vector3d::UnitY());
    PointCloud camera = render_depth(scene.mesh, T, sensor).transformed(T.inverse());
    for (Eigen::Vector3f& p : camera.points) {
      if (is_finite(p)) p *= static_cast<float>(1.0 + kPlanted * p.z());
    }
    f.clouds.push_back(std::move(camera));
    f.poses.push_back(T);
  }
  return f;
}

std::vector<const PointCloud*> views(const Frames& f) {
  std::vector<const PointCloud*> out;
  for (const PointCloud& c : f.clouds) out.push_back(&c);
  return out;
}

TEST(DepthCalibration, FindsAPlantedDepthErrorAndItsCorrectionUndoesIt) {
  Frames f = rendered_frames();
  DepthCalibrationSettings s;
  s.cols = s.rows = 2;
  s.min_gap = 1;
  s.max_gap = 7;
  s.pixel_step = 8;
  const DepthCalibration c = fit_depth_correction(views(f), f.poses, f.intrinsics, s);
  ASSERT_EQ(c.correction.per_metre.size(), 4u);
  // Within 30%: each correspondence reads the other frame's depth at the nearest pixel, a
  // millimetre or so off on a sloping surface, which the planted error (4 mm between these
  // frames) does not dwarf.
  for (double d : c.correction.per_metre) EXPECT_NEAR(d, -kPlanted, 0.3 * kPlanted);
  EXPECT_LT(c.rms_after, 0.5 * c.rms_before) << c.rms_before << " -> " << c.rms_after;

  // Corrected, the frames agree: a second fit finds almost nothing left.
  for (PointCloud& cloud : f.clouds) c.correction.apply(cloud);
  const DepthCalibration again = fit_depth_correction(views(f), f.poses, f.intrinsics, s);
  for (double d : again.correction.per_metre) EXPECT_NEAR(d, 0.0, 0.3 * kPlanted);
  EXPECT_LT(again.rms_before, 0.5 * c.rms_before);
}

TEST(DepthCalibration, RefusesFramesThatCannotBeFitted) {
  Frames f = rendered_frames();
  DepthCorrection wrong_size;
  wrong_size.per_metre = {0.0};
  wrong_size.width = 320;
  EXPECT_THROW(wrong_size.apply(f.clouds[0]), Error);
  // Two frames, one cell each of thousands: too few correspondences.
  DepthCalibrationSettings s;
  s.cols = 64;
  s.rows = 48;
  s.min_gap = 1;
  s.pixel_step = 40;
  f.clouds.resize(2);
  f.poses.resize(2);
  EXPECT_THROW(fit_depth_correction(views(f), f.poses, f.intrinsics, s), Error);
  EXPECT_THROW(fit_depth_correction(views(f), {f.poses[0]}, f.intrinsics, s), Error);
}

}  // namespace
}  // namespace lmk
