// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pbd/collision_scene.h"

#include <cmath>
#include <limits>

#include "lmk/geometry/distance_grid.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/filters.h"
#include "lmk/geometry/kdtree.h"
#include "lmk/geometry/range_image.h"
#include "lmk/geometry/voxel_grid.h"

namespace lmk {

struct CollisionScene::Impl {
  PointCloud points;  // thinned, within reach, off the robot, base frame
  std::unique_ptr<KdTree> tree;
  std::optional<RangeImage> image;     // of the whole frame, for the hidden space
  std::unique_ptr<DistanceGrid> grid;  // the points and the hidden space, over the reach
  CollisionSceneSettings settings;
  std::function<bool(const Eigen::Vector3d&)> robot;  // where the robot stands; may be empty

  // How far `p` lies in front of the hidden space along the sensor's ray (negative: that deep in
  // it), the margin given; nothing where the sensor tells nothing (out of view, no return) or
  // where the robot stands.
  std::optional<double> before_hidden(const Eigen::Vector3d& p) const {
    if (robot && robot(p)) return std::nullopt;
    const RangeImage::Look look = image->look(p.cast<float>());
    if (!look.in_view || !std::isfinite(look.measured)) return std::nullopt;
    return look.measured + settings.hidden_margin - look.depth;
  }
  void index() {
    tree = std::make_unique<KdTree>(points);
    const Box& reach = settings.reach;
    // The reach's axis-aligned bounds in the base frame.
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()),
                    hi = -lo;
    for (const Eigen::Vector3d& corner : reach.corners()) {
      lo = lo.cwiseMin(corner);
      hi = hi.cwiseMax(corner);
    }
    grid = std::make_unique<DistanceGrid>(lo, hi, settings.grid_voxel);
    for (const Eigen::Vector3f& p : points.points) grid->occupy(p.cast<double>());
    if (image) {
      grid->occupy_where([&](const Eigen::Vector3d& c) {
        if (!reach.contains(c)) return false;
        const std::optional<double> before = before_hidden(c);
        return before && *before < 0.0;
      });
    }
    grid->compute();
  }
};

namespace {

bool intended_here(const IntendedContact* intended, const Eigen::Vector3d& p) {
  if (!intended) return false;
  for (const Eigen::Vector3d& n : intended->near) {
    if ((p - n).squaredNorm() <= intended->radius * intended->radius) return true;
  }
  return false;
}

}  // namespace

CollisionScene::CollisionScene(const PointCloud& scene, const CollisionSceneSettings& settings,
                               std::function<bool(const Eigen::Vector3d&)> robot)
    : impl_(std::make_unique<Impl>()) {
  if (!(settings.voxel > 0.0)) throw Error("collision scene: the voxel must be positive");
  if (!(settings.hidden_margin >= 0.0))
    throw Error("collision scene: the hidden margin must not be negative");
  if (!(settings.grid_voxel > 0.0)) throw Error("collision scene: the grid voxel must be positive");
  impl_->settings = settings;
  impl_->robot = std::move(robot);
  impl_->points = voxel_downsample(crop(scene, settings.reach), settings.voxel);
  if (impl_->robot) {
    std::vector<Eigen::Vector3f> kept;
    for (const Eigen::Vector3f& q : impl_->points.points) {
      if (!impl_->robot(q.cast<double>())) kept.push_back(q);
    }
    impl_->points = PointCloud(std::move(kept));
  }
  if (settings.unknown_is_occupied && scene.is_organized())
    impl_->image = RangeImage::from_cloud(scene);
  impl_->index();
}

CollisionScene::~CollisionScene() = default;
CollisionScene::CollisionScene(CollisionScene&&) noexcept = default;

std::size_t CollisionScene::points() const { return impl_->points.size(); }

SceneDistance CollisionScene::distance(const Solid& solid, const Eigen::Isometry3d& T_base_solid,
                                       const std::vector<Eigen::Vector3d>& surface, double within,
                                       const IntendedContact* intended) const {
  SceneDistance best;
  // The grid first: a solid it clears by more than `within` needs no exact measure.
  const double bound = lower_bound(T_base_solid.translation(), solid.bounding_radius());
  if (bound >= within) return {bound, T_base_solid.translation(), false};
  best.distance = std::numeric_limits<double>::infinity();
  const Eigen::Isometry3d T_solid_base = T_base_solid.inverse();
  const float reach = static_cast<float>(solid.bounding_radius() + within);
  std::vector<Neighbor> near;
  impl_->tree->radius_unsorted(T_base_solid.translation().cast<float>(), reach, near);
  for (const Neighbor& n : near) {
    const Eigen::Vector3d p = impl_->points.points[n.index].cast<double>();
    if (intended_here(intended, p)) continue;
    const double d = solid.signed_distance(T_solid_base * p);
    if (d < best.distance) best = {d, p, false};
  }
  if (!impl_->image) return best;
  // The hidden space: how far each surface point lies in front of it along the sensor's ray,
  // where that is nearer than the points' own distance.
  for (const Eigen::Vector3d& s : surface) {
    const Eigen::Vector3d p = T_base_solid * s;
    if (!impl_->settings.reach.contains(p)) continue;
    const std::optional<double> d = impl_->before_hidden(p);
    if (d && *d < best.distance && !intended_here(intended, p)) best = {*d, p, true};
  }
  return best;
}

double CollisionScene::lower_bound(const Eigen::Vector3d& centre, double radius) const {
  return impl_->grid->distance(centre) - impl_->grid->error_bound() - radius;
}

const CollisionSceneSettings& CollisionScene::settings() const { return impl_->settings; }

}  // namespace lmk
