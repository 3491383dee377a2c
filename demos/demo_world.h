// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A simulated world for the PbD demonstrations: objects of the synthetic benchmark's library
// placed around the PR2, in its base frame, with exact ground truth, seen through the head Kinect.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lmk/geometry/point_cloud.h"
#include "lmk/sim/objects.h"

namespace lmk {

/// The floor's height in base_link (the PR2's base_link is 5.1 cm above its footprint).
inline constexpr double kFloorInBase = -0.051;

struct PlacedObject {
  std::string id;
  ObjectModel model;
  Eigen::Isometry3d T_base_object = Eigen::Isometry3d::Identity();
  /// (landmark, part): the object's parts that are instances of the tasks' landmarks.
  std::vector<std::pair<std::string, std::string>> landmarks;
  /// The object whose presence hides this one's landmark instances (a bowl nested under another).
  std::string hidden_by;
};

/// A patch of a surface where an empty-patch landmark may lie: the surface's top face as a box of
/// no height (its pose at the surface, z up), and the landmark's box centre height above it.
struct FreeSurface {
  std::string landmark;
  Box top;
  double box_height = 0.0;
};

class DemoWorld {
 public:
  /// Places `model` at T_base_object; `landmarks` lists its parts that are landmark instances.
  void add(std::string id, ObjectModel model, const Eigen::Isometry3d& T_base_object,
           std::vector<std::pair<std::string, std::string>> landmarks = {});
  /// Removes the object `id` (a picked bowl); throws lmk::Error if there is none.
  void remove(const std::string& id);
  /// While `by` is in the world, `id`'s landmark instances are hidden (not ground truth).
  void hide_under(const std::string& id, const std::string& by);
  void add_free_surface(FreeSurface surface) { surfaces_.push_back(std::move(surface)); }

  const std::vector<PlacedObject>& objects() const { return objects_; }
  /// Changes with every object added or removed: two worlds of the same revision hold the same
  /// objects (one is a copy of the other). For caches of what is built from the objects.
  std::uint64_t revision() const { return revision_; }
  const PlacedObject* object(const std::string& id) const;

  /// Ground-truth boxes of `landmark`, base frame, with the object each belongs to (hidden ones
  /// left out).
  std::vector<std::pair<Box, std::string>> instances(const std::string& landmark) const;

  /// For an empty-patch landmark: the valid patch pose nearest `found`, if one is within 3 cm:
  /// levelled onto the surface under it with the same heading, its footprint on the surface and
  /// its box clear of every object's surface (sampled every 5 mm). Nothing otherwise.
  std::optional<Eigen::Isometry3d> free_patch_near(const std::string& landmark,
                                                   const Box& found) const;
  bool has_free_surface(const std::string& landmark) const;

  /// The floor and every object, as one mesh in the base frame.
  TriangleMesh mesh() const;

  /// What the head Kinect at T_base_sensor sees: an organised cloud in the base frame, with
  /// T_cloud_sensor = T_base_sensor. `seed` drives the depth noise.
  PointCloud observe(const Eigen::Isometry3d& T_base_sensor, std::uint64_t seed) const;

 private:
  std::vector<PlacedObject> objects_;
  std::vector<FreeSurface> surfaces_;
  std::uint64_t revision_ = 0;
};

}  // namespace lmk
