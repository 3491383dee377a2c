// SPDX-License-Identifier: BSD-3-Clause
// The first guess of a landmark box from one click: on rendered tabletops (truth from the
// generator) and on real Kinect frames (the labelled mOSD frames), the guessed box holds the
// object and its margin is empty.
#include "lmk/landmark/box_guess.h"

#include <gtest/gtest.h>

#include <map>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/kdtree.h"
#include "lmk/sim/depth_sensor.h"
#include "lmk/sim/tabletop_scene.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

/// The scene point nearest `target` among `points`: where a user would click.
Index click_on(const PointCloud& scene, const Indices& points, const Eigen::Vector3d& target) {
  Index best = points.front();
  for (Index i : points) {
    if ((scene.points[i].cast<double>() - target).norm() <
        (scene.points[best].cast<double>() - target).norm())
      best = i;
  }
  return best;
}

struct Verdict {
  std::size_t object = 0, held = 0, intruders = 0;
};

/// How many of the object's points the box holds, and how many other points it holds (beyond
/// the supporting surface's noise band, which the box's bottom face rests on).
Verdict judge(const PointCloud& scene, const Indices& object, const BoxGuess& guess) {
  std::vector<bool> is_object(scene.size(), false);
  for (Index i : object) is_object[i] = true;
  Verdict v;
  v.object = object.size();
  for (Index i = 0; i < scene.size(); ++i) {
    if (!is_finite(scene.points[i]) || !guess.box.contains(scene.points[i])) continue;
    if (is_object[i]) {
      ++v.held;
    } else if (!guess.support ||
               guess.support->head<3>().dot(scene.points[i].cast<double>()) + (*guess.support)[3] >
                   0.015) {
      ++v.intruders;
    }
  }
  return v;
}

TEST(BoxGuess, HoldsEachRenderedObjectWithAnEmptyMargin) {
  for (std::uint64_t seed : {1, 2, 3, 4}) {
    const SyntheticScene scene = make_tabletop_scene(seed);
    // Exact depth, so that the generator's boxes say which points are the object's.
    DepthSensorSettings sensor;
    sensor.noise = false;
    const PointCloud cloud = render_depth(scene.mesh, scene.T_world_sensor, sensor);
    for (const SceneObject& truth : scene.objects) {
      // The object's points: those within 2 mm of its true box, above the table top.
      const Box lifted(truth.box.pose * Eigen::Translation3d(0, 0, 0.003),
                       truth.box.size + Eigen::Vector3d(0.004, 0.004, -0.002));
      Indices object;
      for (Index i = 0; i < cloud.size(); ++i) {
        if (is_finite(cloud.points[i]) && lifted.contains(cloud.points[i])) object.push_back(i);
      }
      if (object.size() < 100) continue;  // hidden behind another object in this view
      const Index click = click_on(cloud, object, truth.box.center());
      const BoxGuess guess = guess_box(cloud, cloud.points[click].cast<double>());
      const Verdict v = judge(cloud, object, guess);
      SCOPED_TRACE("seed " + std::to_string(seed) + ", " + truth.name);
      EXPECT_EQ(v.held, v.object);
      EXPECT_LE(v.intruders, 0.01 * v.object) << v.intruders << " other points in the box";
      ASSERT_TRUE(guess.support);
      EXPECT_GT(guess.support->z(), 0.99);  // the table, facing up
      // Some margin of empty space where the neighbours leave room.
      EXPECT_GT(guess.box.size.prod(), guess.object_box.size.prod());
    }
  }
}

TEST(BoxGuess, HoldsLabelledObjectsOfRealKinectFrames) {
  LMK_REQUIRE_SHARED_DATA(data);
  // Every fourth frame of all four parts (boxes, stacked, occluded, cylinders); objects touching
  // another are left out below.
  std::size_t objects = 0;
  for (int frame = 0; frame <= 44; frame += 4) {
    const PointCloud cloud =
        read_cloud((data / "mosd" / "learn" / ("learn" + std::to_string(frame) + ".pcd")).string());
    std::map<std::int32_t, Indices> labelled;
    for (Index i = 0; i < cloud.size(); ++i) {
      if (cloud.labels[i] >= 2 && is_finite(cloud.points[i]))
        labelled[cloud.labels[i]].push_back(i);
    }
    for (const auto& [label, object] : labelled) {
      if (object.size() < 3000) continue;
      // An object within the cluster gap of another cannot be told from it by one click.
      PointCloud others;
      for (const auto& [other, points] : labelled) {
        if (other == label) continue;
        for (Index i : points) others.points.push_back(cloud.points[i]);
      }
      if (!others.empty()) {
        others.set_unorganized();
        const KdTree tree(others);
        double gap = 1e9;
        for (Index i : object) {
          gap = std::min(
              gap, std::sqrt(static_cast<double>(tree.nearest(cloud.points[i])->squared_distance)));
        }
        if (gap < 0.02) continue;
      }
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      for (Index i : object) centroid += cloud.points[i].cast<double>();
      centroid /= static_cast<double>(object.size());
      const Index click = click_on(cloud, object, centroid);
      SCOPED_TRACE("learn" + std::to_string(frame) + ", label " + std::to_string(label));
      const BoxGuess guess = guess_box(cloud, cloud.points[click].cast<double>());
      const Verdict v = judge(cloud, object, guess);
      EXPECT_GE(v.held, 0.99 * v.object) << v.held << " of " << v.object;
      EXPECT_LE(v.intruders, 0.01 * v.object) << v.intruders << " other points in the box";
      ++objects;
    }
  }
  EXPECT_GE(objects, 8u);
}

TEST(BoxGuess, ClicksOffTheObjectAreRefusedWithWhatToDo) {
  const SyntheticScene scene = make_tabletop_scene(1);
  const PointCloud cloud = render_depth(scene.mesh, scene.T_world_sensor, {});
  EXPECT_NE(test::error_of([&] {
              guess_box(cloud, Eigen::Vector3d(50, 50, 50));
            }).find("click on the object"),
            std::string::npos);
  // A point of the bare table (on the support found under the first object), away from every
  // object but near the first: a click beside the object.
  const SceneObject& first = scene.objects.front();
  const BoxGuess on_object = guess_box(cloud, first.box.center());
  ASSERT_TRUE(on_object.support);
  Index table = 0;
  double best = 0.0;
  for (Index i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d p = cloud.points[i].cast<double>();
    if (!p.allFinite() ||
        std::abs(on_object.support->head<3>().dot(p) + (*on_object.support)[3]) > 0.003)
      continue;
    double clearance = 1e9;
    for (const SceneObject& o : scene.objects) {
      clearance = std::min(clearance, (p - o.box.center()).head<2>().norm());
    }
    if ((p - first.box.center()).norm() < 0.4 && clearance > best) {
      best = clearance;
      table = i;
    }
  }
  ASSERT_GT(best, 0.1);
  const std::string error =
      test::error_of([&] { guess_box(cloud, cloud.points[table].cast<double>()); });
  EXPECT_NE(error.find("supporting surface"), std::string::npos) << error;
}

TEST(BoxGuess, LengthsOutsideTheirBoundsAreRefusedBeforeAnyWork) {
  PointCloud cloud;
  cloud.points = {Eigen::Vector3f(0, 0, 1)};
  const auto error_with = [&](auto change) {
    BoxGuessSettings s;
    change(s);
    return test::error_of([&] { guess_box(cloud, Eigen::Vector3d(0, 0, 1), s); });
  };
  EXPECT_NE(error_with([](BoxGuessSettings& s) {
              s.margin = 1e9;
            }).find("margin (--margin): 1e+09 must be finite and in [0, 0.5]"),
            std::string::npos);
  EXPECT_NE(error_with([](BoxGuessSettings& s) { s.margin = -0.01; }).find("margin"),
            std::string::npos);
  EXPECT_NE(error_with([](BoxGuessSettings& s) { s.search_radius = 1e308; }).find("search_radius"),
            std::string::npos);
  EXPECT_NE(
      error_with([](BoxGuessSettings& s) { s.cluster_tolerance = NAN; }).find("cluster_tolerance"),
      std::string::npos);
  EXPECT_NE(error_with([](BoxGuessSettings& s) { s.plane_distance = 0.0; }).find("plane_distance"),
            std::string::npos);
  EXPECT_NO_THROW(validate(BoxGuessSettings()));
}

}  // namespace
}  // namespace lmk
