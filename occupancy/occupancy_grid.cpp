#include "occupancy/occupancy_grid.h"

#include <cmath>

#include "geometry/error.h"
#include "occupancy/detail/vdb_support.h"

namespace lmk {

struct OccupancyGrid::Grid {
  openvdb::BoolGrid::Ptr grid;
  double voxel = 0.0;
};

OccupancyGrid::OccupancyGrid() : OccupancyGrid({}, 0.005) {}

OccupancyGrid::OccupancyGrid(const std::vector<Eigen::Vector3f>& points, double voxel_size) {
  if (!(voxel_size > 0.0 && std::isfinite(voxel_size))) {
    throw Error("occupancy grid: voxel size must be positive and finite");
  }
  detail::initialize_openvdb();
  auto g = std::make_shared<Grid>();
  g->voxel = voxel_size;
  g->grid = openvdb::BoolGrid::create(false);
  g->grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel_size));
  auto access = g->grid->getAccessor();
  for (const auto& p : points) {
    if (p.allFinite()) access.setValueOn(detail::nearest_voxel(p.cast<double>(), voxel_size), true);
  }
  grid_ = std::move(g);
}

double OccupancyGrid::voxel_size() const { return grid_->voxel; }
std::size_t OccupancyGrid::occupied_voxels() const {
  return static_cast<std::size_t>(grid_->grid->activeVoxelCount());
}

struct OccupancyGrid::Sampler::Impl {
  explicit Impl(const Grid& g) : access(g.grid->getConstAccessor()), voxel(g.voxel) {}
  openvdb::BoolGrid::ConstAccessor access;
  double voxel;
};

OccupancyGrid::Sampler::Sampler(const OccupancyGrid& grid)
    : impl_(std::make_unique<Impl>(*grid.grid_)) {}
OccupancyGrid::Sampler::~Sampler() = default;
OccupancyGrid::Sampler::Sampler(Sampler&&) noexcept = default;

bool OccupancyGrid::Sampler::occupied(const Eigen::Vector3f& p) const {
  return p.allFinite() &&
         impl_->access.isValueOn(detail::nearest_voxel(p.cast<double>(), impl_->voxel));
}

}  // namespace lmk
