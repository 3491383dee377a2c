// SPDX-License-Identifier: BSD-3-Clause
// Veil points: the mixed pixels between a foreground edge and the background behind it go, the
// surfaces on either side stay, and a surface seen obliquely (but not edge-on) stays.

#include "lmk/geometry/veil_points.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lmk {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

// A 40 x 30 frame of a pinhole camera at the origin (focal 100 px) looking at a wall at 2 m,
// with a board at 1 m over its left half; column 20, between them, returns depths in between
// (1.5 m), as a real sensor's mixed pixels do.
PointCloud step_frame() {
  PointCloud c;
  c.width = 40;
  c.height = 30;
  for (int v = 0; v < 30; ++v) {
    for (int u = 0; u < 40; ++u) {
      const double z = u < 20 ? 1.0 : u == 20 ? 1.5 : 2.0;
      c.points.emplace_back((u - 20) * z / 100.0, (v - 15) * z / 100.0, z);
    }
  }
  return c;
}

TEST(VeilPoints, TheMixedPixelsOfAnEdgeGoAndTheSurfacesStay) {
  PointCloud c = step_frame();
  const std::size_t removed = remove_veil_points(c, 10 * kDegree);
  EXPECT_EQ(c.width, 40u);
  EXPECT_EQ(c.size(), 1200u);  // organised still
  for (int v = 0; v < 30; ++v) {
    EXPECT_FALSE(is_finite(c.points[v * 40 + 20])) << "the veil pixel of row " << v;
    // The board's last pixel and the wall's first step edge-on to it as well; the rest stays.
    for (int u : {0, 5, 18, 22, 30, 39}) EXPECT_TRUE(is_finite(c.points[v * 40 + u])) << u;
  }
  EXPECT_LE(removed, 3u * 30u);
  EXPECT_GE(removed, 30u);
}

TEST(VeilPoints, AnObliqueSurfaceStays) {
  // A plane seen obliquely: its steps run about 20 degrees off the rays.
  PointCloud c;
  c.width = 20;
  c.height = 20;
  for (int v = 0; v < 20; ++v) {
    for (int u = 0; u < 20; ++u) {
      const double z = 1.0 + 0.02 * v;  // depth grows down the image: a tilted plane
      c.points.emplace_back((u - 10) * z / 500.0, 0.01 * v, z);
    }
  }
  EXPECT_EQ(remove_veil_points(c, 10 * kDegree), 0u);
}

TEST(VeilPoints, OnlyOrganisedCloudsWithAPositiveAngle) {
  PointCloud c = step_frame();
  EXPECT_EQ(remove_veil_points(c, 0.0), 0u);
  c.set_unorganized();
  EXPECT_EQ(remove_veil_points(c, 10 * kDegree), 0u);
  EXPECT_EQ(c.count_finite(), 1200u);
}

}  // namespace
}  // namespace lmk
