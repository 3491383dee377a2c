// SPDX-License-Identifier: BSD-3-Clause
// Fusing depth frames (tsdf_volume.h) on scenes rendered here, where the true surface is known: one
// frame twice is that frame, frames from around a box rebuild the box, and a surface one frame
// measured and two others saw through is decided by weight.

#include "lmk/occupancy/tsdf_volume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "lmk/geometry/error.h"
#include "lmk/geometry/kdtree.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/random.h"
#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/mesh.h"

namespace lmk {
namespace {

constexpr double kVoxel = 0.005;

// A table top 1 m square at z = 0 with a box 20 x 16 x 12 cm on it.
TriangleMesh table_with_box() {
  TriangleMesh world;
  world.append(make_box_mesh({1.0, 1.0, 0.04}), pose_from_xyz_rpy({0, 0, -0.02}, {0, 0, 0}));
  world.append(make_box_mesh({0.2, 0.16, 0.12}), pose_from_xyz_rpy({0, 0, 0.06}, {0, 0, 0.3}));
  return world;
}

// A camera 1.2 m from the table's centre, 45 degrees above it, from the azimuth `degrees`.
Eigen::Isometry3d camera_at(double degrees) {
  const double a = degrees * M_PI / 180.0;
  const Eigen::Vector3d eye(0.85 * std::cos(a), 0.85 * std::sin(a), 0.85);
  return camera_look_at(eye, {0, 0, 0.03}, Eigen::Vector3d::UnitZ());
}

PointCloud render(const TriangleMesh& world, const Eigen::Isometry3d& camera, bool noise,
                  std::uint64_t seed = 0) {
  DepthSensorSettings sensor;
  sensor.noise = noise;
  sensor.seed = seed;
  sensor.width = 320;  // half resolution: the geometry is the same, the test faster
  sensor.height = 240;
  sensor.fx = sensor.fy = 262.5;
  sensor.cx = 159.5;
  sensor.cy = 119.5;
  return render_depth(world, camera, sensor);
}

// The distance from `p` to the nearest face of the axis-aligned box of half sides `half` centred at
// `centre` turned by `yaw` about z.
double distance_to_box(const Eigen::Vector3d& p, const Eigen::Vector3d& centre,
                       const Eigen::Vector3d& half, double yaw) {
  const Eigen::Vector3d local = Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()) * (p - centre);
  const Eigen::Vector3d outside = (local.cwiseAbs() - half).cwiseMax(0.0);
  if (outside.norm() > 0.0) return outside.norm();
  return (half - local.cwiseAbs()).minCoeff();
}

TEST(TsdfVolume, TwoIdenticalFramesGiveOneFramesSurface) {
  const PointCloud frame = render(table_with_box(), camera_at(0), true, 7);
  const PointCloud once = TsdfVolume::fuse({{&frame}}, {}).surface();
  const PointCloud twice = TsdfVolume::fuse({{&frame}, {&frame}}, {}).surface();
  // The same evidence twice is the same average: the same crossings.
  ASSERT_GT(once.size(), 1000u);
  ASSERT_EQ(once.size(), twice.size());
  for (std::size_t i = 0; i < once.size(); ++i) {
    ASSERT_LT((once.points[i] - twice.points[i]).norm(), 1e-5) << i;
  }
  // And the fused frame of a noiseless frame twice, rendered from its own sensor, has its points
  // on the frame's surface within a voxel (against the same view at full resolution, whose points
  // lie 2 mm apart), with a point wherever the frame has one.
  const PointCloud exact = render(table_with_box(), camera_at(0), false);
  const PointCloud fused = fuse_frames({{&exact}, {&exact}});
  ASSERT_EQ(fused.width, exact.width);
  ASSERT_EQ(fused.height, exact.height);
  DepthSensorSettings full;
  full.noise = false;
  const KdTree surface(render_depth(table_with_box(), camera_at(0), full));
  std::size_t both = 0, on_surface = 0;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    if (!is_finite(exact.points[i]) || !is_finite(fused.points[i])) continue;
    ++both;
    if (surface.nearest(fused.points[i])->squared_distance <= kVoxel * kVoxel) ++on_surface;
  }
  EXPECT_GT(both, exact.count_finite() * 99 / 100);
  EXPECT_GT(static_cast<double>(on_surface), 0.99 * static_cast<double>(both));
}

TEST(TsdfVolume, FramesFromAroundABoxRebuildItWithinTwoMillimetres) {
  // Four noisy views, a quarter turn apart, in the world frame (their clouds are already there).
  const TriangleMesh world = table_with_box();
  std::vector<PointCloud> frames;
  for (int k = 0; k < 4; ++k) frames.push_back(render(world, camera_at(90.0 * k + 20.0), true, k));
  std::vector<DepthFrame> fused;
  for (const PointCloud& f : frames) fused.push_back({&f});
  const PointCloud surface = TsdfVolume::fuse(fused, {}).surface();
  // Every crossing on the box's faces (above the table, inside its outline) lies on them: the
  // four frames' noise (2 mm at 1.2 m each) averaged away, and the box's every side present.
  const Eigen::Vector3d centre(0, 0, 0.06), half(0.1, 0.08, 0.06);
  std::vector<double> errors;
  int sides_seen = 0;
  Eigen::Vector4i per_side = Eigen::Vector4i::Zero();
  for (std::size_t i = 0; i < surface.size(); ++i) {
    const Eigen::Vector3d p = surface.points[i].cast<double>();
    if (p.z() < 0.015 || p.z() > 0.14) continue;  // the table, and what is not the box
    const Eigen::Vector3d local = Eigen::AngleAxisd(-0.3, Eigen::Vector3d::UnitZ()) * (p - centre);
    if ((local.head<2>().cwiseAbs() - half.head<2>()).maxCoeff() > 0.02) continue;
    errors.push_back(distance_to_box(p, centre, half, 0.3));
    if (std::abs(local.z()) < 0.05) {
      if (local.x() > 0.095) ++per_side[0];
      if (local.x() < -0.095) ++per_side[1];
      if (local.y() > 0.075) ++per_side[2];
      if (local.y() < -0.075) ++per_side[3];
    }
  }
  for (int s = 0; s < 4; ++s) sides_seen += per_side[s] > 50 ? 1 : 0;
  EXPECT_EQ(sides_seen, 4) << per_side.transpose();
  ASSERT_GT(errors.size(), 1000u);
  std::sort(errors.begin(), errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.002);       // median
  EXPECT_LT(errors[errors.size() * 9 / 10], 0.004);  // the edges' rounding aside
}

TEST(TsdfVolume, ASurfaceOneFrameSawAndTwoSawThroughIsResolvedByWeight) {
  // A sheet 30 cm above the table in one frame (a person's hand, a flying pixel cloud) and absent
  // from two others of the same camera: where the two saw the table through it, it is carved.
  TriangleMesh with_sheet = table_with_box();
  with_sheet.append(make_box_mesh({0.2, 0.2, 0.01}),
                    pose_from_xyz_rpy({0.25, 0.2, 0.3}, {0, 0, 0}));
  const PointCloud once = render(with_sheet, camera_at(0), false);
  const PointCloud empty_a = render(table_with_box(), camera_at(0), false);
  const PointCloud empty_b = render(table_with_box(), camera_at(0), false);
  const Eigen::Vector3d on_sheet(0.25, 0.2, 0.305);
  {
    const TsdfVolume alone = TsdfVolume::fuse({{&once}}, {});
    const auto s = alone.sample(on_sheet);
    ASSERT_TRUE(s);
    EXPECT_LT(std::abs(s->distance), 0.5f);  // the sheet's surface
  }
  const TsdfVolume outvoted = TsdfVolume::fuse({{&once}, {&empty_a}, {&empty_b}}, {});
  const auto s = outvoted.sample(on_sheet);
  ASSERT_TRUE(s);
  EXPECT_GT(s->distance, 0.3f);  // mostly free: two frames against one
  // No crossing is left where the sheet was.
  for (const Eigen::Vector3f& p : outvoted.surface().points) {
    EXPECT_FALSE(std::abs(p.z() - 0.305f) < 0.02f && std::abs(p.x() - 0.25f) < 0.08f &&
                 std::abs(p.y() - 0.2f) < 0.08f)
        << p.transpose();
  }
  // The other way round, two frames with the sheet against one without keep it.
  const TsdfVolume kept = TsdfVolume::fuse({{&once}, {&once}, {&empty_a}}, {});
  const auto k = kept.sample(on_sheet);
  ASSERT_TRUE(k);
  EXPECT_LT(k->distance, 0.5f);
}

TEST(TsdfVolume, FusedFrameHoldsWhatTheOtherFramesSawBeyondTheFirstsEdge) {
  // A bench 3 m long across the view, and a box at its end that the first camera's image cuts off:
  // the second camera, at the same place, turned towards it, sees it.
  TriangleMesh world;
  world.append(make_box_mesh({1.0, 3.0, 0.04}), pose_from_xyz_rpy({0, 0, -0.02}, {0, 0, 0}));
  world.append(make_box_mesh({0.2, 0.2, 0.2}), pose_from_xyz_rpy({0, 1.1, 0.1}, {0, 0, 0}));
  const Eigen::Vector3d eye(0.85, 0, 0.85);
  const PointCloud a =
      render(world, camera_look_at(eye, {0, 0, 0}, Eigen::Vector3d::UnitZ()), false);
  const PointCloud b =
      render(world, camera_look_at(eye, {0, 0.9, 0}, Eigen::Vector3d::UnitZ()), false);
  const auto sees_box_top = [](const PointCloud& c) {
    std::size_t n = 0;
    for (const Eigen::Vector3f& p : c.points) {
      if (is_finite(p) && std::abs(p.z() - 0.2f) < 0.01f && std::abs(p.y() - 1.1f) < 0.09f) ++n;
    }
    return n;
  };
  ASSERT_EQ(sees_box_top(a), 0u);
  ASSERT_GT(sees_box_top(b), 100u);
  const PointCloud fused = fuse_frames({{&a}, {&b}});
  EXPECT_GT(fused.width, a.width);
  EXPECT_LE(fused.width, 2 * a.width);
  EXPECT_LE(fused.height, 2 * a.height);
  EXPECT_GT(sees_box_top(fused), 50u);
  EXPECT_TRUE(fused.T_cloud_sensor.isApprox(a.T_cloud_sensor));
}

TEST(TsdfVolume, OneFrameIsReturnedAsItIsAndBadFramesAreRefused) {
  const PointCloud a = render(table_with_box(), camera_at(0), true, 3);
  const Eigen::Isometry3d moved = pose_from_xyz_rpy({1, 2, 3}, {0.1, 0.2, 0.3});
  const PointCloud one = fuse_frames({{&a, moved}});
  const PointCloud expected = a.transformed(moved);
  ASSERT_EQ(one.size(), expected.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    if (!is_finite(expected.points[i])) continue;
    ASSERT_EQ(one.points[i], expected.points[i]);
  }
  PointCloud unorganised = a;
  unorganised.set_unorganized();
  EXPECT_THROW(TsdfVolume::fuse({{&a}, {&unorganised}}, {}), Error);
  EXPECT_THROW(TsdfVolume::fuse({}, {}), Error);
  EXPECT_THROW(TsdfVolume::fuse(std::vector<DepthFrame>(kMaxFusedFrames + 1, {&a}), {}), Error);
  FusionSettings bad;
  bad.voxel_size = 0.0;
  EXPECT_THROW(TsdfVolume::fuse({{&a}}, bad), Error);
  try {
    TsdfVolume::fuse({{&a}, {&unorganised}}, {});
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("frame 2"), std::string::npos) << e.what();
  }
}

// Issue #61, finding 3: the volume is priced from the frames' points before anything is
// allocated, as a search is, and a volume over settings.max_bytes is refused in one line.
TEST(TsdfVolume, TheVolumeIsPricedBeforeItIsAllocated) {
  const PointCloud a = render(table_with_box(), camera_at(0), true, 3);
  const PointCloud b = render(table_with_box(), camera_at(30), true, 4);
  const std::size_t price = fusion_bytes({{&a}, {&b}}, {});
  FusionSettings fits;
  fits.max_bytes = price;
  const TsdfVolume volume = TsdfVolume::fuse({{&a}, {&b}}, fits);
  // Every observed voxel holds a distance and a weight within the leaves priced.
  EXPECT_LE(volume.observed_voxels() * 2 * sizeof(float), price);
  FusionSettings short_of_it;
  short_of_it.max_bytes = price - 1;
  try {
    TsdfVolume::fuse({{&a}, {&b}}, short_of_it);
    ADD_FAILURE() << "a volume over its limit was fused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the volume would take over"), std::string::npos);
  }
  // The same pixels scattered through a 100 m cube: counting stops at the limit.
  PointCloud scattered = a;
  SplitMix64 rng(61);
  for (Eigen::Vector3f& p : scattered.points) {
    p = Eigen::Vector3f(static_cast<float>(100 * rng.uniform01()),
                        static_cast<float>(100 * rng.uniform01()),
                        static_cast<float>(100 * rng.uniform01()));
  }
  const std::size_t limit = 4 * price;
  EXPECT_GT(fusion_bytes({{&scattered}, {&b}}, {}, limit), limit);
}

}  // namespace
}  // namespace lmk
