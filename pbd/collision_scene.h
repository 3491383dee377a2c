// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The world an arm must not touch (issue #60), from the frames the robot saw: the scenes' points,
// thinned to one per voxel and indexed; the space they hide from the sensor, which counts as
// occupied unless the settings say otherwise; and the space no frame had in view at all, which a
// plan looks at before moving through it (pbd/look_again.h). The points are the frames the
// landmarks were found in; nothing but them and the sensors' rays is known.

#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "lmk/geometry/box.h"
#include "lmk/geometry/point_cloud.h"
#include "lmk/geometry/solid.h"
#include "lmk/pbd/motion_check.h"

namespace lmk {

struct CollisionSceneSettings {
  /// The space the scene's surfaces hide from the sensor (behind what it measured, within its
  /// view) counts as occupied: the arm never sweeps through what nobody saw. False: as free.
  bool unknown_is_occupied = true;
  /// The space no frame had in its view (outside every image, or behind every sensor) counts as
  /// occupied: the arm never goes where no camera looked. Off by
  /// default: one head view leaves most of the arm's way out of sight, and a plan rather looks
  /// there first (LookAgainSettings::unseen_looks) and reports what stayed unseen.
  bool unseen_is_occupied = false;
  /// A point counts as hidden when it lies this much deeper than the surface the sensor measured
  /// along its ray, m: the surface's own thickness and the sensor's noise are not hidden space.
  double hidden_margin = 0.03;
  /// The sensor returns nothing nearer than this depth, m (a PR2 head Kinect's structured light
  /// measures from about half a metre). A ray without a return is free beyond it (nothing was
  /// there to answer) but not before it, where something too near to be measured may stand: a
  /// shelf's roof just in front of the head leaves a hole in the image, not a surface.
  double min_range = 0.5;
  /// ... but only where the image's hole, less the projector's shadows, is at least this wide
  /// (at min_range), m. What stands that near hides every ray behind it: the hole is as wide as
  /// the thing. Narrower holes are the sensor's own dropouts: a grazing face beside a shadow, a
  /// dark edge, between rays that measured far beyond. The price: a thing narrower than this,
  /// nearer the head than min_range (a pole, a board's edge end on), is not seen. At 1 cm the
  /// obstacle scenes' dropouts (strips of 5 to 50 pixels on the floor beside the boxes) fence
  /// the arm in and planning around takes twice as long; at 3 cm they are gone and a shelf's
  /// roof in front of the head is still held (docs/pbd.md, "What the head cannot see").
  double blind_width = 0.03;
  /// The scene's points are thinned to one per voxel of this side, m.
  double voxel = 0.01;
  /// The side of the voxels of the distance grid that clears most of a motion's solids at one
  /// lookup each (geometry/distance_grid.h), m; solids the grid cannot clear are measured exactly.
  double grid_voxel = 0.015;
  /// Only points inside this box (base frame) are obstacles: the arms' reach. The default holds a
  /// PR2's reach and leaves out the floor under it.
  Box reach = Box(Eigen::Translation3d(0.45, 0.0, 0.95) * Eigen::Isometry3d::Identity(),
                  Eigen::Vector3d(1.9, 2.4, 1.9));
  /// The column over the robot's base (the PR2's 0.67 m square, up to its raised head): the
  /// torso, the shoulders and the arms at rest stand there, and the head cannot look down into
  /// it. Its space is never unseen space; its points are obstacles as anywhere.
  Box own_column = Box(Eigen::Translation3d(0.0, 0.0, 0.8) * Eigen::Isometry3d::Identity(),
                       Eigen::Vector3d(0.668, 0.668, 1.7));
};

/// How near a solid comes to the scene.
struct SceneDistance {
  /// Signed: the smallest distance from the solid to a scene point (negative: the point lies that
  /// deep inside), or minus the depth of its surface behind the sensor's measurement where that is
  /// deeper. Beyond the query's reach, only a lower bound (the distance grid's); +infinity when
  /// nothing is known anywhere.
  double distance = 0.0;
  Eigen::Vector3d where = Eigen::Vector3d::Zero();  ///< the nearest point, base frame
  bool hidden = false;  ///< the nearest is space the sensor could not see
  bool unseen =
      false;  ///< ... and no frame had it in view (CollisionSceneSettings::unseen_is_occupied)
};

class CollisionScene {
 public:
  /// `frames`: what the robot saw, each in its base frame with T_cloud_sensor its sensor's pose
  /// (an organised cloud, for the hidden and the unseen space; an unorganised one only gives its
  /// points). Space one frame saw in front of its measurement is free, whatever another hides.
  /// `robot` (optional, base frame): where the robot's own body stands. Its points are the arms as
  /// the sensor saw them, no obstacle to themselves, and its space is neither hidden nor unseen:
  /// nothing else can be there, whatever the sensor saw in front of it.
  CollisionScene(const std::vector<const PointCloud*>& frames,
                 const CollisionSceneSettings& settings = {},
                 std::function<bool(const Eigen::Vector3d&)> robot = nullptr);
  /// One frame.
  explicit CollisionScene(const PointCloud& scene, const CollisionSceneSettings& settings = {},
                          std::function<bool(const Eigen::Vector3d&)> robot = nullptr);
  ~CollisionScene();
  CollisionScene(CollisionScene&&) noexcept;

  /// The distance of `solid` placed at T_base_solid to the scene, looking `within` m beyond its
  /// surface. `surface` holds the solid's surface points (solid frame), for the hidden space.
  /// Scene points the motion intends to touch (`intended`) are no obstacle.
  SceneDistance distance(const Solid& solid, const Eigen::Isometry3d& T_base_solid,
                         const std::vector<Eigen::Vector3d>& surface, double within,
                         const IntendedContact* intended = nullptr) const;

  /// A lower bound of the distance from a sphere at `centre` (base frame) of `radius` to the
  /// scene, from the distance grid alone: one lookup, for a whole link at once.
  double lower_bound(const Eigen::Vector3d& centre, double radius) const;

  /// Whether `p` (base frame) lies within the reach, off the robot, and in no organised frame's
  /// view: space nobody looked at. False everywhere when no frame is organised (nothing says
  /// where the sensor looked).
  bool unseen(const Eigen::Vector3d& p) const;

  std::size_t points() const;
  const CollisionSceneSettings& settings() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lmk
