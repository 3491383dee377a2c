#include "eval/depth_sensor.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "eval/tabletop_scene.h"
#include "geometry/error.h"
#include "geometry/pose.h"

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

TEST(DepthSensor, NoiseMatchesTheKinectModel) {
  DepthSensorSettings s;
  s.seed = 5;
  const double z = 2.0;
  const PointCloud cloud = render_depth(wall(z), Eigen::Isometry3d::Identity(), s);
  double sum = 0, sum2 = 0;
  for (const auto& p : cloud.points) {
    sum += p.z() - z;
    sum2 += (p.z() - z) * (p.z() - z);
  }
  const double n = static_cast<double>(cloud.size());
  const double sigma = 0.0012 + 0.0019 * (z - 0.4) * (z - 0.4);
  // Quantisation at 2 m adds a step of z^2 / (fx b) / 8 = 1.3 mm, i.e. 0.37 mm of uniform noise.
  const double step = z * z / (525.0 * 0.075) / 8.0;
  const double expected = std::sqrt(sigma * sigma + step * step / 12.0);
  EXPECT_NEAR(sum / n, 0.0, 2e-4);
  EXPECT_NEAR(std::sqrt(sum2 / n), expected, 0.05 * expected);
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
