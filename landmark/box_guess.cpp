// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/box_guess.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_plane.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <string>

#include "lmk/geometry/error.h"
#include "lmk/geometry/kdtree.h"
#include "lmk/geometry/oriented_bounding_box.h"

namespace lmk {
namespace {

/// RANSAC's largest plane among `points` (PCL, fixed seed: the same cloud gives the same plane),
/// as n.x + d = 0 with its inliers; nothing when it has fewer than `min_points`. The steps of PCL's
/// SACSegmentation for a plane (RANSAC, then the coefficients refitted to the inliers and the
/// inliers taken again), called on the sample-consensus classes themselves: SACSegmentation's
/// library brings PCL's features, filters and machine learning into every process that loads lmk,
/// about 100,000 symbol bindings at each start (docs/developing.md, "CI's time").
std::optional<std::pair<Eigen::Vector4d, Indices>> largest_plane(const PointCloud& scene,
                                                                 const Indices& points,
                                                                 double distance,
                                                                 std::size_t min_points) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  for (Index i : points) {
    const Eigen::Vector3f& p = scene.points[i];
    cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  }
  if (cloud->empty()) return std::nullopt;
  const auto model = std::make_shared<pcl::SampleConsensusModelPlane<pcl::PointXYZ>>(
      cloud, /*random=*/false);  // false: a fixed seed
  pcl::RandomSampleConsensus<pcl::PointXYZ> ransac(model, distance);
  ransac.setMaxIterations(500);
  if (!ransac.computeModel()) return std::nullopt;
  pcl::Indices inliers;
  ransac.getInliers(inliers);
  Eigen::VectorXf found;
  ransac.getModelCoefficients(found);
  Eigen::VectorXf refined;
  model->optimizeModelCoefficients(inliers, found, refined);
  model->selectWithinDistance(refined, distance, inliers);
  if (inliers.size() < min_points) return std::nullopt;
  Eigen::Vector4d plane = refined.cast<double>();
  plane /= plane.head<3>().norm();
  Indices members;
  for (int k : inliers) members.push_back(points[static_cast<std::size_t>(k)]);
  return std::make_pair(plane, members);
}

double signed_distance(const Eigen::Vector4d& plane, const Eigen::Vector3f& p) {
  return plane.head<3>().dot(p.cast<double>()) + plane[3];
}

/// The points connected to `start` through gaps below `tolerance`, among those `allowed`.
Indices grow_cluster(const PointCloud& scene, const KdTree& tree, Index start,
                     const std::vector<bool>& allowed, float tolerance) {
  std::vector<bool> seen(scene.size(), false);
  Indices cluster;
  std::deque<Index> queue{start};
  seen[start] = true;
  std::vector<Neighbor> near;
  while (!queue.empty()) {
    const Index i = queue.front();
    queue.pop_front();
    cluster.push_back(i);
    tree.radius_unsorted(scene.points[i], tolerance, near);
    for (const Neighbor& n : near) {
      if (!seen[n.index] && allowed[n.index]) {
        seen[n.index] = true;
        queue.push_back(n.index);
      }
    }
  }
  std::sort(cluster.begin(), cluster.end());
  return cluster;
}

/// Grows `object` by up to `margin` on each of its six sides, less on a side where a point of
/// `others` would fall inside: each such point limits the side it lies furthest beyond, so that
/// the margin stays empty (the paper's empty-space term counts on it).
Box grow_by_empty_margin(const Box& object, const PointCloud& scene, Indices others, double margin,
                         const std::optional<Eigen::Vector4d>& support, double plane_distance) {
  const Eigen::Vector3d half = 0.5 * object.size;
  std::array<double, 6> grow;  // -x, +x, -y, +y, -z, +z
  grow.fill(margin);
  const Eigen::Isometry3d T_box_scene = object.pose.inverse();
  // The face towards the support stops at it: an object standing on a table gets no margin into
  // the table, and the table's points then limit no other side.
  if (support) {
    const Eigen::Vector3d n = object.pose.linear().transpose() * support->head<3>();  // box frame
    int axis = 0;
    n.cwiseAbs().maxCoeff(&axis);
    if (std::abs(n[axis]) > std::cos(15.0 * M_PI / 180.0)) {
      const int side = 2 * axis + (n[axis] > 0.0 ? 0 : 1);  // the face whose normal is -n
      const Eigen::Vector3d centre = object.pose.translation();
      const double gap = support->head<3>().dot(centre) + (*support)[3] - half[axis];
      // The object's own lowest points lie within plane_distance of the support and are not in
      // the cluster: reach down to the support itself (2 mm short of it), or by the margin when
      // the support is farther away (a wall behind a hanging object).
      grow[side] = gap <= margin + plane_distance ? std::max(0.0, gap - 0.002) : margin;
      others.erase(std::remove_if(others.begin(), others.end(),
                                  [&](Index i) {
                                    return signed_distance(*support, scene.points[i]) <=
                                           plane_distance;
                                  }),
                   others.end());
    }
  }
  // The neighbours in the box frame, moved there once and taken nearest first, so that each
  // limit comes from the closest neighbour on its side.
  std::vector<Eigen::Vector3d> neighbours;
  neighbours.reserve(others.size());
  for (Index i : others) neighbours.push_back(T_box_scene * scene.points[i].cast<double>());
  std::sort(neighbours.begin(), neighbours.end(),
            [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
              return a.cwiseAbs().maxCoeff() < b.cwiseAbs().maxCoeff();
            });
  for (const Eigen::Vector3d& p : neighbours) {
    int side = -1;
    double beyond = 0.0;
    bool inside_grown = true;
    for (int axis = 0; axis < 3; ++axis) {
      const bool positive = p[axis] > 0.0;
      const double excess = std::abs(p[axis]) - half[axis];  // > 0: outside the object's box
      const int s = 2 * axis + (positive ? 1 : 0);
      if (excess > grow[s]) inside_grown = false;
      if (excess > beyond) {
        beyond = excess;
        side = s;
      }
    }
    // Inside the grown box but outside the object's: that side stops short of the point.
    if (inside_grown && side >= 0) grow[side] = std::max(0.0, beyond - 0.002);
  }
  Eigen::Vector3d low, high;
  for (int axis = 0; axis < 3; ++axis) {
    low[axis] = -half[axis] - grow[2 * axis];
    high[axis] = half[axis] + grow[2 * axis + 1];
  }
  Eigen::Isometry3d pose = object.pose;
  pose.translation() = object.pose * (0.5 * (low + high));
  return Box(pose, high - low);
}

}  // namespace

void validate(const BoxGuessSettings& s) { validate_settings(s, "box guess: "); }

BoxGuess guess_box(const PointCloud& scene, const Eigen::Vector3d& clicked,
                   const BoxGuessSettings& settings) {
  validate(settings);
  if (!clicked.allFinite()) throw Error("box guess: the clicked point is not finite");
  const KdTree tree(scene);
  const Eigen::Vector3f click = clicked.cast<float>();
  std::vector<Neighbor> near = tree.radius(click, static_cast<float>(settings.search_radius));
  if (near.empty()) {
    throw Error("box guess: no scene point within " +
                std::to_string(static_cast<int>(settings.search_radius * 100)) +
                " cm of the click; click on the object");
  }
  const Index start = near.front().index;  // the scene point the user clicked
  Indices neighbourhood;
  for (const Neighbor& n : near) neighbourhood.push_back(n.index);

  // The supporting surface: the largest plane around the click (a table, a shelf board, a wall).
  // A click on it is a click beside the object.
  BoxGuess guess;
  std::vector<bool> allowed(scene.size(), false);
  for (Index i : neighbourhood) allowed[i] = true;
  if (const auto plane =
          largest_plane(scene, neighbourhood, settings.plane_distance, settings.min_plane_points)) {
    Eigen::Vector4d n = plane->first;
    const double click_side = signed_distance(n, scene.points[start]);
    if (std::abs(click_side) <= settings.plane_distance) {
      throw Error(
          "box guess: the clicked point lies on the supporting surface (the largest "
          "plane around it, such as a table or a wall); click on the object");
    }
    if (click_side < 0.0) n = -n;  // the normal points to the object
    guess.support = n;
    // The support and everything behind it (a table's legs, the floor) is not the object.
    for (Index i : neighbourhood) {
      if (signed_distance(n, scene.points[i]) <= settings.plane_distance) allowed[i] = false;
    }
  }
  guess.object =
      grow_cluster(scene, tree, start, allowed, static_cast<float>(settings.cluster_tolerance));
  if (guess.object.size() < settings.min_points) {
    throw Error("box guess: only " + std::to_string(guess.object.size()) +
                " points around the click (at least " + std::to_string(settings.min_points) +
                "); click on a larger object, or draw the box by hand");
  }
  // Standing on its support the box is upright on it (its footprint's minimum rectangle);
  // otherwise CGAL's optimal oriented box.
  guess.object_box = guess.support
                         ? upright_bounding_box(scene.select(guess.object), *guess.support)
                         : oriented_bounding_box(scene.select(guess.object));
  std::vector<bool> in_object(scene.size(), false);
  for (Index i : guess.object) in_object[i] = true;
  const float reach = static_cast<float>(0.5 * guess.object_box.size.norm() + settings.margin);
  Indices others;
  for (const Neighbor& n : tree.radius(guess.object_box.pose.translation().cast<float>(), reach)) {
    if (!in_object[n.index]) others.push_back(n.index);
  }
  guess.box = grow_by_empty_margin(guess.object_box, scene, others, settings.margin, guess.support,
                                   settings.plane_distance);
  return guess;
}

}  // namespace lmk
