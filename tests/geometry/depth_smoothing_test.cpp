// SPDX-License-Identifier: BSD-3-Clause
// Depth smoothing: a tilted plane quantised into a Kinect's terraces comes back onto the plane, a
// step between two surfaces stays a step, near points and holes are left alone, and each point
// moves along its own ray.

#include "lmk/geometry/depth_smoothing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace lmk {
namespace {

constexpr int kWidth = 60, kHeight = 40;
constexpr double kFocal = 300.0;

// A pinhole frame (sensor at the origin, optical frame) of the surface z = depth(u, v), each depth
// rounded to the sensor's levels as a Kinect rounds them when `levels` is set.
template <class Depth>
PointCloud frame(Depth depth, bool levels) {
  const DepthNoise noise;
  PointCloud c;
  c.width = kWidth;
  c.height = kHeight;
  for (int v = 0; v < kHeight; ++v) {
    for (int u = 0; u < kWidth; ++u) {
      double z = depth(u, v);
      if (levels) {
        const double step = noise.level_coefficient * z * z;
        z = step * std::round(z / step);
      }
      c.points.emplace_back((u - kWidth / 2) * z / kFocal, (v - kHeight / 2) * z / kFocal, z);
    }
  }
  return c;
}

// A plane at 2.4 m tilted 60 degrees about the vertical, as a cupboard seen obliquely: z = 2.4 +
// tan(60) x, met by the ray of pixel u where x = z (u - cx) / f.
double tilted(int u, int) { return 2.4 / (1.0 - std::tan(1.047) * (u - kWidth / 2) / kFocal); }

// Each point's distance from the true plane, RMS over the frame's inner part (away from its border,
// where the window is cut).
double plane_rms(const PointCloud& c) {
  double sum = 0.0;
  int n = 0;
  for (int v = 5; v < kHeight - 5; ++v) {
    for (int u = 5; u < kWidth - 5; ++u) {
      const Eigen::Vector3f& p = c.points[static_cast<std::size_t>(v) * kWidth + u];
      // The plane z = 2.4 + tan(60) x, in the frame's coordinates.
      const double off = (p.z() - 2.4 - std::tan(1.047) * p.x()) * std::cos(1.047);
      sum += off * off;
      ++n;
    }
  }
  return std::sqrt(sum / n);
}

TEST(DepthSmoothing, PutsATerracedPlaneBackOnThePlaneAlongEachRay) {
  PointCloud c = frame(tilted, true);
  const PointCloud raw = c;
  const double before = plane_rms(c);
  smooth_depth(c, 2);
  const double after = plane_rms(c);
  EXPECT_GT(before, 0.002);  // terraces about 15 mm apart at 2.4 m
  EXPECT_LT(after, 0.5 * before) << before << " -> " << after;
  for (std::size_t i = 0; i < c.size(); ++i) {  // along its own ray: the direction is unchanged
    EXPECT_NEAR(c.points[i].normalized().dot(raw.points[i].normalized()), 1.0, 1e-6);
  }
}

TEST(DepthSmoothing, KeepsAStepBetweenTwoSurfacesSharp) {
  // A board at 2.0 m over the left half, a wall at 2.3 m: 30 cm, many levels apart.
  PointCloud c = frame([](int u, int) { return u < kWidth / 2 ? 2.0 : 2.3; }, false);
  smooth_depth(c, 3);
  for (int v = 0; v < kHeight; ++v) {
    for (int u = 0; u < kWidth; ++u) {
      EXPECT_FLOAT_EQ(c.points[static_cast<std::size_t>(v) * kWidth + u].z(),
                      u < kWidth / 2 ? 2.0f : 2.3f);
    }
  }
}

TEST(DepthSmoothing, LeavesNearPointsHolesAndUnorganisedCloudsAlone) {
  // Nearer than kDepthSmoothingFrom, a Kinect's levels are finer than its pixels: nothing moves.
  PointCloud near = frame([](int u, int) { return 1.2 + 0.01 * (u % 3); }, false);
  const PointCloud raw_near = near;
  smooth_depth(near, 2);
  EXPECT_EQ(near.points, raw_near.points);

  PointCloud holes = frame(tilted, true);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  holes.points[100] = Eigen::Vector3f(nan, nan, nan);
  smooth_depth(holes, 2);
  EXPECT_FALSE(is_finite(holes.points[100]));
  for (std::size_t i = 0; i < holes.size(); ++i) {
    if (i != 100) {
      EXPECT_TRUE(is_finite(holes.points[i])) << i;
    }
  }

  PointCloud flat = frame(tilted, true);
  flat.set_unorganized();
  const PointCloud raw_flat = flat;
  smooth_depth(flat, 2);
  EXPECT_EQ(flat.points, raw_flat.points);
  PointCloud off = frame(tilted, true);
  const PointCloud raw_off = off;
  smooth_depth(off, 0);
  EXPECT_EQ(off.points, raw_off.points);
}

TEST(DepthSmoothing, FollowsTheSensorPose) {
  // The same terraced plane, expressed in a frame where the sensor stands elsewhere, smooths to the
  // same points moved with it.
  PointCloud local = frame(tilted, true);
  const Eigen::Isometry3d T = Eigen::Translation3d(1.0, -0.5, 0.3) *
                              Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.3, 1.0, 0.2).normalized());
  PointCloud moved = local.transformed(T);
  ASSERT_TRUE(moved.T_cloud_sensor.isApprox(T));
  smooth_depth(local, 2);
  smooth_depth(moved, 2);
  for (std::size_t i = 0; i < local.size(); ++i) {
    EXPECT_LT((moved.points[i] - (T.cast<float>() * local.points[i])).norm(), 1e-4f) << i;
  }
}

}  // namespace
}  // namespace lmk
