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
  PointCloud points;  // thinned, within reach, base frame
  std::unique_ptr<KdTree> tree;
  std::optional<RangeImage> image;     // of the whole frame, for the hidden space
  std::unique_ptr<DistanceGrid> grid;  // the points and the hidden space, over the reach
  CollisionSceneSettings settings;
  std::function<bool(const Eigen::Vector3d&)> known_free;

  bool hidden(const Eigen::Vector3d& p) const {
    if (known_free && known_free(p)) return false;
    const RangeImage::Look look = image->look(p.cast<float>());
    return look.in_view && std::isfinite(look.measured) &&
           look.depth > look.measured + settings.hidden_margin;
  }
  void index() {
    tree = std::make_unique<KdTree>(points);
    const Box& reach = settings.reach;
    const Eigen::Vector3d half = 0.5 * reach.size;
    // The reach's axis-aligned bounds in the base frame.
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d local((corner & 1 ? 1 : -1) * half.x(),
                                  (corner & 2 ? 1 : -1) * half.y(),
                                  (corner & 4 ? 1 : -1) * half.z());
      const Eigen::Vector3d p = reach.pose * local;
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    grid = std::make_unique<DistanceGrid>(lo, hi, settings.grid_voxel);
    for (const Eigen::Vector3f& p : points.points) grid->occupy(p.cast<double>());
    if (image) {
      grid->occupy_where([&](const Eigen::Vector3d& c) { return reach.contains(c) && hidden(c); });
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

CollisionScene::CollisionScene(const PointCloud& scene, const CollisionSceneSettings& settings)
    : impl_(std::make_unique<Impl>()), settings_(settings) {
  if (!(settings.voxel > 0.0)) throw Error("collision scene: the voxel must be positive");
  if (!(settings.hidden_margin >= 0.0))
    throw Error("collision scene: the hidden margin must not be negative");
  if (!(settings.grid_voxel > 0.0)) throw Error("collision scene: the grid voxel must be positive");
  impl_->settings = settings;
  impl_->points = voxel_downsample(crop(scene, settings.reach), settings.voxel);
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
  // The hidden space: how far each surface point lies behind what the sensor measured on its ray
  // (along the ray, the margin given), where that is nearer than the points' own distance.
  for (const Eigen::Vector3d& s : surface) {
    const Eigen::Vector3d p = T_base_solid * s;
    if (!settings_.reach.contains(p)) continue;
    if (impl_->known_free && impl_->known_free(p)) continue;
    const RangeImage::Look look = impl_->image->look(p.cast<float>());
    if (!look.in_view || !std::isfinite(look.measured)) continue;
    const double d = look.measured + settings_.hidden_margin - look.depth;
    if (d < best.distance && !intended_here(intended, p)) best = {d, p, true};
  }
  return best;
}

double CollisionScene::lower_bound(const Eigen::Vector3d& centre, double radius) const {
  return impl_->grid->distance(centre) - impl_->grid->error_bound() - radius;
}

void CollisionScene::set_known_free(std::function<bool(const Eigen::Vector3d&)> known_free) {
  impl_->known_free = std::move(known_free);
  if (impl_->image) impl_->index();
}

void CollisionScene::remove_points(const std::function<bool(const Eigen::Vector3d&)>& is_robot) {
  std::vector<Eigen::Vector3f> kept;
  for (const Eigen::Vector3f& q : impl_->points.points) {
    if (!is_robot(q.cast<double>())) kept.push_back(q);
  }
  if (kept.size() == impl_->points.size()) return;
  impl_->points = PointCloud(std::move(kept));
  impl_->index();
}

}  // namespace lmk
