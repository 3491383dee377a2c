// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/sim/depth_sensor.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <limits>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/sim/tabletop_scene.h"

namespace lmk {
namespace {

// A large wall facing a sensor at the origin, `distance` metres away along the optical axis.
TriangleMesh wall(double distance) {
  TriangleMesh mesh;
  mesh.append(make_box_mesh({20.0, 20.0, 0.01}),
              pose_from_xyz_rpy({0, 0, distance + 0.005}, {0, 0, 0}));
  return mesh;
}

TEST(DepthSensor, ExactDepthOnAFrontoParallelWall) {
  DepthSensorSettings s;
  s.noise = false;
  const PointCloud cloud = render_depth(wall(2.0), Eigen::Isometry3d::Identity(), s);
  EXPECT_EQ(cloud.width, 640u);
  EXPECT_EQ(cloud.height, 480u);
  EXPECT_EQ(cloud.count_finite(), cloud.size());
  for (int v : {0, 240, 479}) {
    for (int u : {0, 320, 639}) {
      const Eigen::Vector3f p = cloud.points[v * 640 + u];
      EXPECT_NEAR(p.z(), 2.0, 1e-6);
      // Pinhole projection: u = fx x / z + cx.
      EXPECT_NEAR(525.0 * p.x() / p.z() + 319.5, u, 1e-4);
      EXPECT_NEAR(525.0 * p.y() / p.z() + 239.5, v, 1e-4);
    }
  }
}

// A painted mesh gives colour registered to the depth: the paint times the light's gain, shaded;
// an unpainted one gives depth only, as it always did.
TEST(DepthSensor, APaintedMeshGivesColourThatFollowsTheLight) {
  DepthSensorSettings s;
  s.noise = false;
  s.colour_noise = 0.0;
  EXPECT_FALSE(render_depth(wall(2.0), Eigen::Isometry3d::Identity(), s).has_colors());
  const TriangleMesh red = painted(wall(2.0), Color{200, 40, 30});
  const PointCloud bright = render_depth(red, Eigen::Isometry3d::Identity(), s);
  s.light = Eigen::Vector3d::Constant(0.5);
  const PointCloud dim = render_depth(red, Eigen::Isometry3d::Identity(), s);
  ASSERT_TRUE(bright.has_colors() && dim.has_colors());
  const std::size_t centre = 240 * 640 + 320;
  const Color b = bright.colors[centre], d = dim.colors[centre];
  EXPECT_EQ(b.r, 200);  // the wall faces the sensor squarely: fully lit
  EXPECT_EQ(b.g, 40);
  EXPECT_NEAR(d.r, 100, 1);
  EXPECT_NEAR(d.g, 20, 1);
  EXPECT_NEAR(d.b, 15, 1);
}

TEST(DepthSensor, NoiseMatchesTheKinectModel) {
  DepthSensorSettings s;
  s.seed = 5;
  s.flying_pixel_rate = 0.0;  // a wall has no depth edge anyway
  const double z = 2.0;
  const PointCloud cloud = render_depth(wall(z), Eigen::Isometry3d::Identity(), s);
  double sum = 0, sum2 = 0;
  for (const auto& p : cloud.points) {
    sum += p.z() - z;
    sum2 += (p.z() - z) * (p.z() - z);
  }
  const double n = static_cast<double>(cloud.size());
  const double sigma = s.noise_a + s.noise_b * (z - s.noise_z0) * (z - s.noise_z0);
  // Quantisation at 2 m adds levels z^2 / (f b) / 8 = 11.5 mm apart, i.e. 3.3 mm of uniform
  // noise, when the noise spreads the points over several levels as here.
  const double step = depth_level_spacing(z, s);
  EXPECT_NEAR(step, z * z / (580.0 * 0.075) / 8.0, 1e-12);
  const double expected = std::sqrt(sigma * sigma + step * step / 12.0);
  EXPECT_NEAR(sum / n, 0.0, 5e-4);
  EXPECT_NEAR(std::sqrt(sum2 / n), expected, 0.05 * expected);
}

// The disparity's levels, then whole millimetres: what the real sensor's driver reports.
TEST(DepthSensor, DepthComesInDisparityLevelsAndMillimetres) {
  DepthSensorSettings s;
  s.noise_b = 0.0;  // exact depth, quantised only
  for (double z : {0.7, 1.3, 2.5, 3.5}) {
    const double reported = sensor_depth(z, 0.0, s);
    EXPECT_NEAR(reported * 1000.0, std::round(reported * 1000.0), 1e-9) << z;
    // Within half a level (and half a millimetre) of the truth.
    EXPECT_LE(std::abs(reported - z), 0.5 * depth_level_spacing(z, s) + 0.0005 + 1e-9) << z;
    // Depths a level apart report different values; depths a tenth of a level apart mostly not.
    EXPECT_NE(sensor_depth(z + depth_level_spacing(z, s), 0.0, s), reported) << z;
  }
}

// A box in front of a wall: the projector, 7.5 cm to the camera's +x, cannot light the wall just
// left of the box (as the image shows it), so those pixels return nothing; right of it they do.
TEST(DepthSensor, ProjectorShadowLiesLeftOfObjects) {
  DepthSensorSettings s;
  s.noise = false;
  TriangleMesh scene = wall(2.0);
  scene.append(make_box_mesh({0.2, 0.2, 0.2}), pose_from_xyz_rpy({0, 0, 1.0}, {0, 0, 0}));
  const PointCloud with = render_depth(scene, Eigen::Isometry3d::Identity(), s);
  s.shadows = false;
  const PointCloud without = render_depth(scene, Eigen::Isometry3d::Identity(), s);
  EXPECT_EQ(without.count_finite(), without.size());
  const int v = 240;
  std::vector<int> shadowed;
  for (int u = 0; u < 640; ++u) {
    if (!is_finite(with.points[v * 640 + u])) shadowed.push_back(u);
  }
  ASSERT_FALSE(shadowed.empty());
  // The box's left face is at u = 319.5 - 525 * 0.1 / 0.9 (its front at 0.9 m hides the rest);
  // the shadow on the wall at 2 m spans the projector's offset seen from there: from the box's
  // left edge on the wall (x = -0.1 * 2 / 0.9 ... the ray past the edge) about f b (1/0.9 - 1/2)
  // pixels wide.
  const double left_edge = 319.5 - 525.0 * 0.1 / 0.9;
  const double width = 525.0 * 0.075 * (1.0 / 0.9 - 1.0 / 2.0);
  EXPECT_NEAR(shadowed.back(), left_edge, 2.0);
  EXPECT_NEAR(static_cast<double>(shadowed.size()), width, 2.0);
  for (int u : shadowed) EXPECT_LT(u, 320);
}

// Flying pixels only at depth edges, and only between the two surfaces.
TEST(DepthSensor, FlyingPixelsLieBetweenTheSurfacesAtDepthEdges) {
  DepthSensorSettings s;
  s.noise_b = 0.0;
  s.shadows = false;
  s.flying_pixel_rate = 1.0;
  TriangleMesh scene = wall(2.0);
  scene.append(make_box_mesh({0.4, 0.4, 0.2}), pose_from_xyz_rpy({0, 0, 1.1}, {0, 0, 0}));
  const PointCloud cloud = render_depth(scene, Eigen::Isometry3d::Identity(), s);
  std::size_t flying = 0;
  for (const auto& p : cloud.points) {
    if (!is_finite(p)) continue;
    const double z = p.z();
    const bool on_a_surface = std::abs(z - 1.0) < 0.002 || std::abs(z - 2.0) < 0.02;
    if (on_a_surface) continue;
    ++flying;
    EXPECT_GT(z, 1.0);
    EXPECT_LT(z, 2.0);
    // Only next to the box's outline: within a pixel of its edges seen from the sensor.
    const double u = 525.0 * p.x() / z + 319.5, v = 525.0 * p.y() / z + 239.5;
    const double half = 525.0 * 0.2 / 1.0;
    const bool near_edge =
        std::abs(std::abs(u - 319.5) - half) < 2.0 || std::abs(std::abs(v - 239.5) - half) < 2.0;
    EXPECT_TRUE(near_edge) << u << " " << v;
  }
  EXPECT_GT(flying, 4u * 150u);  // the box's outline is 4 x 210 pixels long, both sides of it
}

TEST(DepthSensor, NoReturnOutsideTheRange) {
  DepthSensorSettings s;
  s.noise = false;
  EXPECT_EQ(render_depth(wall(0.3), Eigen::Isometry3d::Identity(), s).count_finite(), 0u);
  EXPECT_EQ(render_depth(wall(4.5), Eigen::Isometry3d::Identity(), s).count_finite(), 0u);
}

TEST(DepthSensor, NoReturnAtGrazingIncidence) {
  DepthSensorSettings s;
  s.noise = false;
  // A floor 0.5 m below a sensor looking along it: far pixels see it at grazing angles.
  TriangleMesh floor;
  floor.append(make_box_mesh({20, 0.01, 20}), pose_from_xyz_rpy({0, 0.505, 0}, {0, 0, 0}));
  const PointCloud cloud = render_depth(floor, Eigen::Isometry3d::Identity(), s);
  const Eigen::Vector3d up(0, -1, 0);
  for (const auto& p : cloud.points) {
    if (!is_finite(p)) continue;
    const double cos_incidence = std::abs(up.dot(p.cast<double>().normalized()));
    EXPECT_GE(cos_incidence, std::cos(s.max_incidence) - 1e-9);
  }
  EXPECT_GT(cloud.count_finite(), 1000u);
  EXPECT_LT(cloud.count_finite(), 640u * 240u);
}

TEST(DepthSensor, DeterministicWhateverTheThreadCount) {
  const SyntheticScene scene = make_tabletop_scene(3);
  DepthSensorSettings s;
  s.seed = 3;
  PointCloud one, two;
  tbb::task_arena(1).execute([&] { one = render_depth(scene.mesh, scene.T_world_sensor, s); });
  tbb::task_arena(2).execute([&] { two = render_depth(scene.mesh, scene.T_world_sensor, s); });
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_TRUE(one.points[i] == two.points[i] ||
                (!is_finite(one.points[i]) && !is_finite(two.points[i])));
  }
}

// The nearest triangle along pixel (u, v)'s ray, by testing every triangle (Moller & Trumbore):
// the depth along the optical axis, or NaN.
double nearest_depth_by_brute_force(const TriangleMesh& mesh,
                                    const Eigen::Isometry3d& T_world_sensor,
                                    const DepthSensorSettings& s, int u, int v) {
  const Eigen::Vector3d origin = T_world_sensor.translation();
  const Eigen::Vector3d d =
      T_world_sensor.linear() * Eigen::Vector3d((u - s.cx) / s.fx, (v - s.cy) / s.fy, 1.0);
  double nearest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]], e1 = mesh.vertices[t[1]] - a,
                          e2 = mesh.vertices[t[2]] - a;
    const Eigen::Vector3d p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-15) continue;
    const Eigen::Vector3d o = origin - a, q = o.cross(e1);
    const double b1 = o.dot(p) / det, b2 = d.dot(q) / det, z = e2.dot(q) / det;
    if (b1 >= 0 && b2 >= 0 && b1 + b2 <= 1 && z >= 0) nearest = std::min(nearest, z);
  }
  return nearest >= s.min_range && nearest <= s.max_range ? nearest : std::nan("");
}

// The tree's search skips the triangles a ray certainly misses (sim/depth_sensor.cpp): every pixel
// still sees the nearest surface along its ray, as testing every triangle finds it; a skipped
// nearest triangle would show a farther surface behind it. A few pixels see nothing, before this
// search as after it: where CGAL's nearest intersection is a segment (a ray in a triangle's plane,
// as when grazing), the sensor returns nothing. Those are holes, never another surface.
TEST(DepthSensor, EveryPixelSeesTheNearestSurfaceAlongItsRay) {
  const SyntheticScene scene = make_tabletop_scene(5);
  DepthSensorSettings s;
  s.noise = false;
  s.shadows = false;
  s.max_incidence = M_PI / 2;  // every facing accepted: depth alone is compared
  s.width = 80;
  s.height = 60;
  s.fx = s.fy = 525.0 / 8;
  s.cx = 39.5;
  s.cy = 29.5;
  const PointCloud cloud = render_depth(scene.mesh, scene.T_world_sensor, s);
  const Eigen::Isometry3d T_sensor_world = scene.T_world_sensor.inverse();
  std::size_t surfaces = 0, holes = 0;
  for (int v = 0; v < s.height; ++v) {
    for (int u = 0; u < s.width; ++u) {
      const double expected =
          nearest_depth_by_brute_force(scene.mesh, scene.T_world_sensor, s, u, v);
      const Eigen::Vector3f& p = cloud.points[static_cast<std::size_t>(v) * s.width + u];
      if (std::isnan(expected)) {
        EXPECT_FALSE(is_finite(p)) << "pixel " << u << ", " << v;
        continue;
      }
      ++surfaces;
      if (!is_finite(p)) {
        ++holes;
        continue;
      }
      EXPECT_NEAR((T_sensor_world * p.cast<double>()).z(), expected, 1e-5) << u << ", " << v;
    }
  }
  EXPECT_GT(surfaces, static_cast<std::size_t>(s.width * s.height / 2));
  EXPECT_LE(100 * holes, surfaces) << holes << " holes in " << surfaces << " surface pixels";
}

TEST(DepthSensor, RejectsBadSettings) {
  DepthSensorSettings s;
  s.max_range = 0.1;
  EXPECT_THROW(render_depth(wall(1.0), Eigen::Isometry3d::Identity(), s), Error);
}

TEST(TabletopScene, ObjectsRestOnTheTableInViewAndDifferBySeed) {
  const SyntheticScene a = make_tabletop_scene(1), b = make_tabletop_scene(2);
  ASSERT_EQ(a.objects.size(), 3u);
  DepthSensorSettings s;
  s.noise = false;
  const PointCloud cloud = render_depth(a.mesh, a.T_world_sensor, s);
  for (const SceneObject& object : a.objects) {
    SCOPED_TRACE(object.name);
    EXPECT_NEAR(object.box.center().z() - 0.5 * object.box.size.z(), 0.72, 1e-9);
    // The sensor sees the object: some points lie inside its box.
    int inside = 0;
    for (const auto& p : cloud.points) inside += is_finite(p) && object.box.contains(p);
    EXPECT_GT(inside, 50);
  }
  EXPECT_GT((a.objects[0].box.center() - b.objects[0].box.center()).norm(), 1e-3);
}

}  // namespace
}  // namespace lmk
