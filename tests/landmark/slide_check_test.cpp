// SPDX-License-Identifier: BSD-3-Clause
// The slide check on hand-built shapes, whose free motions are known: an edge slides along itself,
// a plane slides in itself and turns about its normal, a cylinder slides along and turns about its
// axis, a sphere turns about its centre, and a corner is fixed.

#include "lmk/landmark/slide_check.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lmk {
namespace {

constexpr double kNoise = 0.003;

void add(PointCloud& c, const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
  c.points.push_back(p.cast<float>());
  c.normals.push_back(n.normalized().cast<float>());
}

// A square patch of side 0.1 m spanned by u and v from `origin`, normal u x v.
void add_patch(PointCloud& c, const Eigen::Vector3d& origin, const Eigen::Vector3d& u,
               const Eigen::Vector3d& v) {
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) add(c, origin + 0.005 * i * u + 0.005 * j * v, u.cross(v));
}

double distance_to_line(const Eigen::Vector3d& point, const Slide& s) {
  const Eigen::Vector3d d = point - s.through;
  return (d - d.dot(s.axis) * s.axis).norm();
}

TEST(SlideCheck, AnEdgeSlidesAlongItselfOnly) {
  PointCloud c;
  add_patch(c, {0, 0, 0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());  // z = 0
  add_patch(c, {0, 0, 0}, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX());  // y = 0
  const SlideReport r = slide_check(c, kNoise);
  ASSERT_EQ(r.slides.size(), 1u);
  EXPECT_FALSE(r.slides[0].turn);
  EXPECT_NEAR(std::abs(r.slides[0].axis.x()), 1.0, 1e-6);
  EXPECT_TRUE(std::isinf(r.slides[0].extent));
  const Box box(Eigen::Isometry3d::Identity(), {0.2, 0.2, 0.2});
  const std::vector<std::string> lines = describe_slides(r, box);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "slides freely along the box's x within the noise");
  EXPECT_NE(lines[1].find("widen the box"), std::string::npos);
}

TEST(SlideCheck, ACornerIsFixed) {
  PointCloud c;
  add_patch(c, {0, 0, 0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
  add_patch(c, {0, 0, 0}, Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ());
  add_patch(c, {0, 0, 0}, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX());
  EXPECT_TRUE(slide_check(c, kNoise).slides.empty());
  EXPECT_TRUE(describe_slides(slide_check(c, kNoise), Box()).empty());
}

TEST(SlideCheck, APlaneSlidesInItselfAndTurnsAboutItsNormal) {
  PointCloud c;
  add_patch(c, {0, 0, 0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
  const SlideReport r = slide_check(c, kNoise);
  ASSERT_EQ(r.slides.size(), 3u);
  int turns = 0;
  for (const Slide& s : r.slides) {
    if (s.turn) {
      ++turns;
      EXPECT_NEAR(std::abs(s.axis.z()), 1.0, 1e-6);
    } else {
      EXPECT_NEAR(s.axis.z(), 0.0, 1e-6);
    }
  }
  EXPECT_EQ(turns, 1);
}

TEST(SlideCheck, ACylinderSlidesAlongAndTurnsAboutItsAxis) {
  PointCloud c;
  const double radius = 0.04;
  for (int a = 0; a < 30; ++a) {  // the half facing -y, as a sensor on that side sees it
    const double angle = M_PI + M_PI * a / 29.0;
    for (int k = 0; k < 20; ++k) {
      const Eigen::Vector3d n(std::cos(angle), std::sin(angle), 0.0);
      add(c, Eigen::Vector3d(0.3, 0.2, 0.0) + radius * n + Eigen::Vector3d(0, 0, 0.005 * k), n);
    }
  }
  const SlideReport r = slide_check(c, kNoise);
  ASSERT_EQ(r.slides.size(), 2u);
  bool slide = false, turn = false;
  for (const Slide& s : r.slides) {
    EXPECT_NEAR(std::abs(s.axis.z()), 1.0, 1e-6);
    if (s.turn) {
      turn = true;
      EXPECT_LT(distance_to_line({0.3, 0.2, 0.0}, s), 1e-3);  // about the cylinder's own axis
    } else {
      slide = true;
    }
  }
  EXPECT_TRUE(slide && turn);
}

TEST(SlideCheck, ASphereTurnsAboutItsCentre) {
  PointCloud c;
  const Eigen::Vector3d centre(0.1, -0.2, 1.0);
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 40; ++j) {  // the cap facing the sensor at the origin
      const double polar = 0.1 + 1.3 * i / 19.0, azimuth = 2.0 * M_PI * j / 40.0;
      const Eigen::Vector3d n(std::sin(polar) * std::cos(azimuth),
                              std::sin(polar) * std::sin(azimuth), -std::cos(polar));
      add(c, centre + 0.05 * n, n);
    }
  }
  const SlideReport r = slide_check(c, kNoise);
  ASSERT_EQ(r.slides.size(), 3u);
  for (const Slide& s : r.slides) {
    EXPECT_TRUE(s.turn);
    EXPECT_LT(distance_to_line(centre, s), 1e-3);
  }
}

TEST(SlideCheck, ASlightFeatureBoundsTheSlideByTheNoise) {
  // An edge with a 1 cm bump: sliding along it is constrained, but weakly. The extent follows the
  // noise: doubling the noise doubles it.
  PointCloud c;
  add_patch(c, {0, 0, 0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
  add_patch(c, {0, 0, 0}, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX());
  for (int j = 0; j < 10; ++j) add(c, {0.05, 0.001 * j, 0.001 * j}, {1, 0, 0});
  const SlideReport a = slide_check(c, kNoise), b = slide_check(c, 2 * kNoise);
  ASSERT_EQ(a.slides.size(), 1u);
  ASSERT_EQ(b.slides.size(), 1u);
  EXPECT_TRUE(std::isfinite(a.slides[0].extent));
  EXPECT_GT(a.slides[0].extent, kSlideReportSigmas * kNoise);
  EXPECT_NEAR(b.slides[0].extent, 2.0 * a.slides[0].extent, 1e-9);
  const std::vector<std::string> lines =
      describe_slides(a, Box(Eigen::Isometry3d::Identity(), {1, 1, 1}));
  EXPECT_NE(lines[0].find(" cm along the box's x"), std::string::npos) << lines[0];
}

}  // namespace
}  // namespace lmk
