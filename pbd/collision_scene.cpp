// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pbd/collision_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lmk/geometry/distance_grid.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/filters.h"
#include "lmk/geometry/image_mask.h"
#include "lmk/geometry/kdtree.h"
#include "lmk/geometry/projector_shadow.h"
#include "lmk/geometry/range_image.h"
#include "lmk/geometry/voxel_grid.h"

namespace lmk {

namespace {

// The holes of one image where something nearer than the sensor's minimum range may stand: its
// pixels without a return, in holes at least CollisionSceneSettings::blind_width wide at that
// range (narrower ones are dropouts between rays that measured beyond), and how far every pixel
// lies from them.
class BlindHoles {
 public:
  BlindHoles(const PointCloud& frame, const RangeImage& image,
             const CollisionSceneSettings& settings)
      : focal_(std::min(image.intrinsics().fx, image.intrinsics().fy)) {
    if (!(settings.min_range > 0.0)) return;
    const PinholeIntrinsics& k = image.intrinsics();
    std::vector<std::uint8_t> none(image.depths().size());
    for (std::size_t i = 0; i < none.size(); ++i) none[i] = std::isnan(image.depths()[i]);
    // A projector's shadow is explained: its rays are lit, hence empty, up to the shadow volume
    // behind a surface the sensor measured (geometry/projector_shadow.h).
    for (const ShadowRay& ray : projector_shadow_rays(frame)) none[ray.pixel] = 0;
    const double pixels = settings.blind_width * focal_ / settings.min_range;
    const std::vector<std::uint8_t> holes =
        open_mask(none, k.width, k.height, static_cast<int>(std::floor(0.5 * pixels)));
    if (std::find(holes.begin(), holes.end(), 1) != holes.end())
      pixels_away_ = distance_to_mask(holes, k.width, k.height);
  }
  // A hole's own pixels are those no distance away from one.
  bool hole(std::size_t pixel) const {
    return !pixels_away_.empty() && pixels_away_[pixel] == 0.0f;
  }
  // A lower bound of the distance from a point at `depth` on the ray of `pixel` to the rays of the
  // holes, at that depth, m; +infinity without holes.
  double beside(std::size_t pixel, double depth) const {
    if (pixels_away_.empty()) return std::numeric_limits<double>::infinity();
    return pixels_away_[pixel] * depth / focal_;
  }

 private:
  double focal_;
  std::vector<float> pixels_away_;  // per pixel, to the nearest hole; empty: no hole
};

}  // namespace

struct CollisionScene::Impl {
  PointCloud points;  // thinned, within reach, off the robot, base frame
  std::unique_ptr<KdTree> tree;
  std::vector<RangeImage> images;      // of the organised frames, for the hidden and unseen space
  std::vector<BlindHoles> blind;       // per image
  std::unique_ptr<DistanceGrid> grid;  // the points and the hidden space, over the reach
  CollisionSceneSettings settings;
  std::function<bool(const Eigen::Vector3d&)> robot;  // where the robot stands; may be empty

  // What the frames say of `p`, off the robot: how far it lies in front of the hidden space along
  // the ray of the frame that sees it best, the margin given (negative: that deep in it, hidden
  // from every frame that has it in view); nothing where some frame measured nothing along its
  // ray. Out of every frame's view: minus how far it lies outside the nearest view when unseen
  // space counts as occupied, else nothing. `unseen` says which.
  // `nearer_than`: only an answer nearer than that is wanted (the robot is not asked otherwise).
  std::optional<double> before_hidden(
      const Eigen::Vector3d& p, bool* unseen = nullptr,
      double nearer_than = std::numeric_limits<double>::infinity()) const {
    bool out_of_view = false;
    const std::optional<double> said = seen_by_frames(p, out_of_view);
    // The robot's own space is never hidden nor unseen (asked last, and only where the answer
    // counts: it is the dearer question, a planner's check asks it of every surface point).
    if (!said || !(*said < nearer_than) || (robot && robot(p))) return std::nullopt;
    if (unseen) *unseen = out_of_view;
    return said;
  }
  // before_hidden() without the robot.
  std::optional<double> seen_by_frames(const Eigen::Vector3d& p, bool& out_of_view) const {
    if (!settings.unknown_is_occupied && !settings.unseen_is_occupied) return std::nullopt;
    double best = -std::numeric_limits<double>::infinity(), outside = best;
    bool in_any_view = false;
    const bool in_column = settings.own_column.contains(p);
    for (std::size_t i = 0; i < images.size(); ++i) {
      const RangeImage& image = images[i];
      const RangeImage::Look look = image.look(p.cast<float>());
      if (!look.in_view) {
        if (settings.unseen_is_occupied) outside = std::max(outside, -outside_view(image, p));
        continue;
      }
      in_any_view = true;
      // Over the robot's base, only its own body stands too near the head to be measured.
      best = std::max(best, frame_says(look, in_column ? nullptr : &blind[i]));
    }
    if (in_any_view) {
      if (!settings.unknown_is_occupied || best == std::numeric_limits<double>::infinity())
        return std::nullopt;
      return best;
    }
    if (images.empty() || !settings.unseen_is_occupied || in_column) return std::nullopt;
    out_of_view = true;
    return outside;
  }
  // What one frame says of a point in its view (`look`): how far it lies in front of the space the
  // frame hid, m (negative: that deep in it); +infinity where the frame saw along the ray and
  // beyond, up to its range, without a return (nothing stood there).
  // `holes`: the frame's (BlindHoles), or none.
  double frame_says(const RangeImage::Look& look, const BlindHoles* holes) const {
    const bool near = holes && look.depth < settings.min_range;
    if (near && holes->hole(look.pixel)) return look.depth - settings.min_range;
    double says = std::isfinite(look.measured) ? look.measured + settings.hidden_margin - look.depth
                                               : std::numeric_limits<double>::infinity();
    // Beside a hole, what stands too near to be measured is as near as the hole's edge: nothing
    // measured marks that edge, so the distance to it is the padding's only guard.
    if (near) says = std::min(says, holes->beside(look.pixel, look.depth));
    return says;
  }
  // How far `p`, out of `image`'s view, lies outside it, m: its distance across the image's edge
  // at its depth, or behind the sensor; at least a millimetre.
  static double outside_view(const RangeImage& image, const Eigen::Vector3d& p) {
    const double depth = image.depth_of(p.cast<float>());
    const std::optional<Eigen::Vector2d> uv = image.project(p.cast<float>());
    if (!uv || !(depth > 0.0)) return std::max(1e-3, -depth);
    const PinholeIntrinsics& k = image.intrinsics();
    const double du = std::max({0.0, -uv->x(), uv->x() - (k.width - 1)});
    const double dv = std::max({0.0, -uv->y(), uv->y() - (k.height - 1)});
    return std::max(1e-3, std::max(du / k.fx, dv / k.fy) * depth);
  }
  bool in_some_view(const Eigen::Vector3d& p) const {
    for (const RangeImage& image : images)
      if (image.look(p.cast<float>()).in_view) return true;
    return false;
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
    if (!images.empty() && (settings.unknown_is_occupied || settings.unseen_is_occupied)) {
      grid->occupy_where([&](const Eigen::Vector3d& c) {
        if (!reach.contains(c)) return false;
        bool out_of_view = false;
        const std::optional<double> said = seen_by_frames(c, out_of_view);
        return said && *said < 0.0 && !(robot && robot(c));
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
    : CollisionScene(std::vector<const PointCloud*>{&scene}, settings, std::move(robot)) {}

CollisionScene::CollisionScene(const std::vector<const PointCloud*>& frames,
                               const CollisionSceneSettings& settings,
                               std::function<bool(const Eigen::Vector3d&)> robot)
    : impl_(std::make_unique<Impl>()) {
  if (!(settings.voxel > 0.0)) throw Error("collision scene: the voxel must be positive");
  if (!(settings.hidden_margin >= 0.0))
    throw Error("collision scene: the hidden margin must not be negative");
  if (!(settings.min_range >= 0.0))
    throw Error("collision scene: the sensor's minimum range must not be negative");
  if (!(settings.blind_width >= 0.0))
    throw Error("collision scene: the blind width must not be negative");
  if (!(settings.grid_voxel > 0.0)) throw Error("collision scene: the grid voxel must be positive");
  impl_->settings = settings;
  impl_->robot = std::move(robot);
  std::vector<Eigen::Vector3f> seen;
  for (const PointCloud* frame : frames) {
    const PointCloud within = crop(*frame, settings.reach);
    seen.insert(seen.end(), within.points.begin(), within.points.end());
    if (!frame->is_organized()) continue;
    if (std::optional<RangeImage> image = RangeImage::from_cloud(*frame)) {
      impl_->blind.emplace_back(*frame, *image, settings);
      impl_->images.push_back(std::move(*image));
    }
  }
  impl_->points = voxel_downsample(PointCloud(std::move(seen)), settings.voxel);
  if (impl_->robot) {
    std::vector<Eigen::Vector3f> kept;
    for (const Eigen::Vector3f& q : impl_->points.points) {
      if (!impl_->robot(q.cast<double>())) kept.push_back(q);
    }
    impl_->points = PointCloud(std::move(kept));
  }
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
  if (impl_->images.empty() ||
      !(impl_->settings.unknown_is_occupied || impl_->settings.unseen_is_occupied))
    return best;
  // The hidden space: how far each surface point lies in front of it along the sensor's ray,
  // where that is nearer than the points' own distance.
  for (const Eigen::Vector3d& s : surface) {
    const Eigen::Vector3d p = T_base_solid * s;
    if (!impl_->settings.reach.contains(p)) continue;
    bool unseen = false;
    if (intended_here(intended, p)) continue;
    const std::optional<double> d = impl_->before_hidden(p, &unseen, best.distance);
    if (d) best = {*d, p, true, unseen};
  }
  return best;
}

double CollisionScene::lower_bound(const Eigen::Vector3d& centre, double radius) const {
  return impl_->grid->distance(centre) - impl_->grid->error_bound() - radius;
}

bool CollisionScene::unseen(const Eigen::Vector3d& p) const {
  const CollisionSceneSettings& s = impl_->settings;
  if (impl_->images.empty() || !s.reach.contains(p) || s.own_column.contains(p)) return false;
  if (impl_->in_some_view(p)) return false;
  return !impl_->robot || !impl_->robot(p);
}

const CollisionSceneSettings& CollisionScene::settings() const { return impl_->settings; }

}  // namespace lmk
