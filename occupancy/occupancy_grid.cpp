// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/occupancy/occupancy_grid.h"

#include <Eigen/Geometry>
#include <cmath>
#include <optional>

#include "lmk/geometry/error.h"
#include "lmk/occupancy/detail/vdb_support.h"

namespace lmk {

struct OccupancyGrid::Grid {
  openvdb::BoolGrid::Ptr grid;
  double voxel = 0.0;
};

OccupancyGrid::OccupancyGrid() : OccupancyGrid({}, 0.005) {}

OccupancyGrid::OccupancyGrid(const std::vector<Eigen::Vector3f>& points, double voxel_size,
                             const StopCheck& stop) {
  if (!(voxel_size > 0.0 && std::isfinite(voxel_size))) {
    throw Error("occupancy grid: voxel size must be positive and finite");
  }
  detail::initialize_openvdb();
  auto g = std::make_shared<Grid>();
  g->voxel = voxel_size;
  g->grid = openvdb::BoolGrid::create(false);
  g->grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel_size));
  auto access = g->grid->getAccessor();
  const double inverse_voxel = 1.0 / voxel_size;
  // Neighbouring pixels of a frame often fall in one voxel: a voxel just set is not set again (the
  // accessor's call was a third of the grid's build).
  std::optional<openvdb::Coord> last;
  for (std::size_t i = 0; i < points.size(); ++i) {
    check_every(stop, i);
    const Eigen::Vector3f& p = points[i];
    if (!p.allFinite()) continue;
    const openvdb::Coord voxel = detail::nearest_voxel(p.cast<double>(), inverse_voxel);
    if (last == voxel) continue;
    access.setValueOn(voxel, true);
    last = voxel;
  }
  grid_ = std::move(g);
}

double OccupancyGrid::voxel_size() const { return grid_->voxel; }
std::size_t OccupancyGrid::occupied_voxels() const {
  return static_cast<std::size_t>(grid_->grid->activeVoxelCount());
}

std::vector<Eigen::Vector3f> OccupancyGrid::occupied_in(const Box& box) const {
  using Leaf = openvdb::BoolTree::LeafNodeType;
  std::vector<Eigen::Vector3f> out;
  // Finite is enough: poses from registration may be a few 1e-6 off orthonormal.
  if (!box.pose.matrix().allFinite() || !box.size.allFinite()) return out;
  const double voxel = grid_->voxel;
  Eigen::AlignedBox3d bounds;
  for (const Eigen::Vector3d& c : box.corners()) bounds.extend(c);
  const openvdb::Coord first = detail::nearest_voxel(bounds.min(), 1.0 / voxel);
  const openvdb::Coord last = detail::nearest_voxel(bounds.max(), 1.0 / voxel);
  const auto leaf_origin = [](int v) { return v & ~static_cast<int>(Leaf::DIM - 1); };
  const auto access = grid_->grid->getConstAccessor();
  for (int x = leaf_origin(first.x()); x <= last.x(); x += Leaf::DIM) {
    for (int y = leaf_origin(first.y()); y <= last.y(); y += Leaf::DIM) {
      for (int z = leaf_origin(first.z()); z <= last.z(); z += Leaf::DIM) {
        const Leaf* leaf = access.probeConstLeaf(openvdb::Coord(x, y, z));
        if (leaf == nullptr) continue;
        for (auto it = leaf->cbeginValueOn(); it; ++it) {
          const openvdb::Coord c = it.getCoord();
          const Eigen::Vector3d centre = Eigen::Vector3d(c.x(), c.y(), c.z()) * voxel;
          if (box.contains(centre)) out.push_back(centre.cast<float>());
        }
      }
    }
  }
  return out;
}

struct OccupancyGrid::Sampler::Impl {
  // Unregistered: the grid never changes once built.
  explicit Impl(const Grid& g)
      : access(g.grid->getConstUnsafeAccessor()), inverse_voxel(1.0 / g.voxel) {}
  openvdb::BoolGrid::ConstUnsafeAccessor access;
  double inverse_voxel;
};

OccupancyGrid::Sampler::Sampler(const OccupancyGrid& grid)
    : impl_(std::make_unique<Impl>(*grid.grid_)) {}
OccupancyGrid::Sampler::~Sampler() = default;
OccupancyGrid::Sampler::Sampler(Sampler&&) noexcept = default;

bool OccupancyGrid::Sampler::occupied(const Eigen::Vector3f& p) const {
  return p.allFinite() &&
         impl_->access.isValueOn(detail::nearest_voxel(p.cast<double>(), impl_->inverse_voxel));
}

}  // namespace lmk
