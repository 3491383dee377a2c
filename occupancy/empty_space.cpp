// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/occupancy/empty_space.h"

#include <openvdb/math/DDA.h>
#include <openvdb/math/Ray.h>

#include <algorithm>
#include <cmath>

#include "lmk/geometry/error.h"
#include "lmk/occupancy/detail/vdb_support.h"
#include "lmk/occupancy/internal/grids.h"

namespace lmk {
namespace {

namespace vdb = openvdb;

// The part [t0, t1] of the segment a + t (b - a), t in [0, 1], inside the axis-aligned box of
// half-sides `half` centred at the origin (slab method). False when they do not meet.
bool clip_to_box(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& half,
                 double& t0, double& t1) {
  t0 = 0.0, t1 = 1.0;
  const Eigen::Vector3d d = b - a;
  for (int axis = 0; axis < 3; ++axis) {
    if (std::abs(d[axis]) < 1e-12) {
      if (std::abs(a[axis]) > half[axis]) return false;
      continue;
    }
    double near = (-half[axis] - a[axis]) / d[axis], far = (half[axis] - a[axis]) / d[axis];
    if (near > far) std::swap(near, far);
    t0 = std::max(t0, near), t1 = std::min(t1, far);
    if (t0 > t1) return false;
  }
  return true;
}

// lmk::Error naming the first input the observation cannot use.
void check_observation(const std::vector<RayBundle>& views, const Box& box,
                       const EmptySpaceSettings& settings) {
  const double voxel = settings.voxel_size, margin = settings.surface_margin;
  const double unobserved_margin = settings.unobserved_margin;
  if (!(voxel > 0.0 && std::isfinite(voxel))) {
    throw Error("empty space: voxel size must be positive and finite");
  }
  if (!(margin >= 0.0 && std::isfinite(margin))) {
    throw Error("empty space: the surface margin must be finite and non-negative");
  }
  if (!(unobserved_margin >= 0.0 && std::isfinite(unobserved_margin))) {
    throw Error("empty space: the unobserved margin must be finite and non-negative");
  }
  if (!box.is_valid()) throw Error("empty space: the box needs a finite pose and positive sides");
  for (const RayBundle& view : views) {
    if (!view.origin.allFinite()) throw Error("empty space: the sensor origin is not finite");
    if (view.ends == nullptr) throw Error("empty space: a view without rays");
  }
}

// Every voxel of the box a ray crossed, up to the surface margin before its end point. The free
// ones are chosen from these once all rays are in (free_voxels()).
vdb::BoolGrid::Ptr crossed_voxels(const std::vector<RayBundle>& views, const Box& box,
                                  const EmptySpaceSettings& settings) {
  const double voxel = settings.voxel_size, margin = settings.surface_margin;
  auto crossed = vdb::BoolGrid::create(false);
  crossed->setTransform(vdb::math::Transform::createLinearTransform(voxel));
  auto access = crossed->getAccessor();
  const Eigen::Isometry3d T_box_capture = box.pose.inverse();
  const Eigen::Vector3d half = 0.5 * box.size;
  for (const RayBundle& view : views) {
    const Eigen::Vector3d& sensor_origin = view.origin;
    const Eigen::Vector3d origin_in_box = T_box_capture * sensor_origin;
    const vdb::Vec3d eye(sensor_origin.x() / voxel + 0.5, sensor_origin.y() / voxel + 0.5,
                         sensor_origin.z() / voxel + 0.5);  // DDA cells are [i, i+1): shift by half
    for (const auto& point : *view.ends) {
      if (!point.allFinite()) continue;
      const Eigen::Vector3d p = point.cast<double>();
      double t0 = 0.0, t1 = 0.0;
      if (!clip_to_box(origin_in_box, T_box_capture * p, half, t0, t1)) continue;
      const double length = (p - sensor_origin).norm();
      if (length <= margin) continue;
      // Free space ends `margin` before the surface the ray hit.
      t1 = std::min(t1, 1.0 - margin / length);
      if (t0 >= t1) continue;
      const Eigen::Vector3d d = (p - sensor_origin) / voxel;
      const vdb::math::Ray<double> ray(eye, vdb::Vec3d(d.x(), d.y(), d.z()), t0, t1);
      vdb::math::DDA<vdb::math::Ray<double>, 0> dda(ray, t0, t1);
      do {
        const vdb::Coord& ijk = dda.voxel();
        if (access.isValueOn(ijk)) continue;
        const Eigen::Vector3d centre = Eigen::Vector3d(ijk.x(), ijk.y(), ijk.z()) * voxel;
        if (box.contains(centre)) access.setValueOn(ijk, true);
      } while (dda.step());
    }
  }
  return crossed;
}

// A crossed voxel is free when it lies the surface margin from every measured surface (the
// landmark's points) and the unobserved margin from every voxel of the box that no ray crossed.
// Unobserved space may hold a surface the sensor never returned: the far side of an object, or a
// face seen so obliquely that the sensor dropped its depth. Rays that graze such a face cross the
// voxels just outside it, and with no measured point there nothing else kept them from being
// called free; seen from another side, the face then stood in the landmark's "empty" space (on
// the viewpoints preset, a tide bottle seen from its right had 1-2% of its empty space occupied by
// its own right face, and was rejected).
vdb::BoolGrid::Ptr free_voxels(const vdb::BoolGrid& crossed, const Box& box,
                               const DistanceField& surface, const EmptySpaceSettings& settings) {
  const double voxel = settings.voxel_size, margin = settings.surface_margin;
  const double unobserved_margin = settings.unobserved_margin;
  const int reach = static_cast<int>(std::floor(unobserved_margin / voxel));
  auto access = crossed.getConstAccessor();
  // Unobserved: in the box and crossed by no ray. Rays sparser than the voxels (a capture from
  // beyond about 3 m, where a Kinect's pixels lie more than 5 mm apart) leave gaps in open air
  // that count as unobserved too: the free space then shrinks, which is never wrong.
  const auto unobserved = [&](const vdb::Coord& ijk) {
    if (access.isValueOn(ijk)) return false;
    return box.contains(Eigen::Vector3d(Eigen::Vector3d(ijk.x(), ijk.y(), ijk.z()) * voxel));
  };
  const auto near_unobserved = [&](const vdb::Coord& c) {
    for (int i = -reach; i <= reach; ++i) {
      for (int j = -reach; j <= reach; ++j) {
        for (int k = -reach; k <= reach; ++k) {
          if ((i * i + j * j + k * k) * voxel * voxel >
              unobserved_margin * unobserved_margin * (1.0 + 1e-9)) {
            continue;
          }
          if (unobserved(c.offsetBy(i, j, k))) return true;
        }
      }
    }
    return false;
  };
  const auto surface_sampler = surface.sampler();
  auto free = vdb::BoolGrid::create(false);
  free->setTransform(vdb::math::Transform::createLinearTransform(voxel));
  auto free_access = free->getAccessor();
  for (auto it = crossed.cbeginValueOn(); it; ++it) {
    const vdb::Coord c = it.getCoord();
    const Eigen::Vector3f centre(static_cast<float>(c.x() * voxel),
                                 static_cast<float>(c.y() * voxel),
                                 static_cast<float>(c.z() * voxel));
    if (surface_sampler.distance(centre) < margin || near_unobserved(c)) continue;
    free_access.setValueOn(c, true);
  }
  return free;
}

}  // namespace

EmptySpaceGrid::EmptySpaceGrid() {
  detail::initialize_openvdb();
  auto g = std::make_shared<Grid>();
  g->grid = vdb::BoolGrid::create(false);
  g->grid->setTransform(vdb::math::Transform::createLinearTransform(0.005));
  grid_ = std::move(g);
}

EmptySpaceGrid EmptySpaceGrid::observe(const std::vector<Eigen::Vector3f>& scene_points,
                                       const Eigen::Vector3d& sensor_origin, const Box& box,
                                       const DistanceField& surface,
                                       const EmptySpaceSettings& settings) {
  return observe_views({RayBundle{&scene_points, sensor_origin}}, box, surface, settings);
}

EmptySpaceGrid EmptySpaceGrid::observe_views(const std::vector<RayBundle>& views, const Box& box,
                                             const DistanceField& surface,
                                             const EmptySpaceSettings& settings) {
  check_observation(views, box, settings);
  detail::initialize_openvdb();
  const vdb::BoolGrid::Ptr crossed = crossed_voxels(views, box, settings);
  vdb::BoolGrid::Ptr free = free_voxels(*crossed, box, surface, settings);
  free->setName("empty");
  return from_grid(Grid{free, {}});
}

double EmptySpaceGrid::voxel_size() const { return grid_->grid->voxelSize()[0]; }
std::size_t EmptySpaceGrid::size() const { return grid_->centres.size(); }
const std::vector<Eigen::Vector3f>& EmptySpaceGrid::centres() const { return grid_->centres; }

bool EmptySpaceGrid::is_empty(const Eigen::Vector3f& p) const { return sampler().is_empty(p); }

struct EmptySpaceGrid::Sampler::Impl {
  explicit Impl(std::shared_ptr<const Grid> g)
      : grid(std::move(g)),
        access(grid->grid->getConstUnsafeAccessor()),
        inverse_voxel(1.0 / grid->grid->voxelSize()[0]) {}
  std::shared_ptr<const Grid> grid;
  vdb::BoolGrid::ConstUnsafeAccessor access;  // unregistered: the grid never changes once built
  double inverse_voxel;
};

EmptySpaceGrid::Sampler::Sampler(const EmptySpaceGrid& grid)
    : impl_(std::make_unique<Impl>(grid.grid_)) {}
EmptySpaceGrid::Sampler::~Sampler() = default;
EmptySpaceGrid::Sampler::Sampler(Sampler&&) noexcept = default;

bool EmptySpaceGrid::Sampler::is_empty(const Eigen::Vector3f& p) const {
  return p.allFinite() &&
         impl_->access.isValueOn(detail::nearest_voxel(p.cast<double>(), impl_->inverse_voxel));
}

const EmptySpaceGrid::Grid& EmptySpaceGrid::grid() const { return *grid_; }

std::vector<Eigen::Vector3i> EmptySpaceGrid::voxels() const {
  std::vector<Eigen::Vector3i> out;
  out.reserve(size());
  for (auto it = grid_->grid->cbeginValueOn(); it; ++it) {
    const vdb::Coord c = it.getCoord();
    out.emplace_back(c.x(), c.y(), c.z());
  }
  std::sort(out.begin(), out.end(), [](const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  return out;
}

EmptySpaceGrid EmptySpaceGrid::from_voxels(double voxel_size,
                                           const std::vector<Eigen::Vector3i>& voxels) {
  if (!(voxel_size > 0.0) || !std::isfinite(voxel_size)) {
    throw Error("empty space: the voxel side " + std::to_string(voxel_size) +
                " is not positive and finite");
  }
  detail::initialize_openvdb();
  const vdb::BoolGrid::Ptr grid = vdb::BoolGrid::create(false);
  grid->setTransform(vdb::math::Transform::createLinearTransform(voxel_size));
  grid->setName("empty");
  auto access = grid->getAccessor();
  for (const Eigen::Vector3i& v : voxels) access.setValueOn(vdb::Coord(v.x(), v.y(), v.z()), true);
  return from_grid(Grid{grid, {}});
}

EmptySpaceGrid EmptySpaceGrid::from_grid(Grid grid) {
  if (!grid.grid) throw Error("empty space: missing grid");
  // The centres, in OpenVDB's iteration order: deterministic for a given set of voxels.
  const double voxel = grid.grid->voxelSize()[0];
  grid.centres.clear();
  for (auto it = grid.grid->cbeginValueOn(); it; ++it) {
    const vdb::Coord c = it.getCoord();
    grid.centres.emplace_back(static_cast<float>(c.x() * voxel), static_cast<float>(c.y() * voxel),
                              static_cast<float>(c.z() * voxel));
  }
  EmptySpaceGrid out;
  out.grid_ = std::make_shared<Grid>(std::move(grid));
  return out;
}

}  // namespace lmk
