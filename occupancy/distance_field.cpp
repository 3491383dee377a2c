// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/occupancy/distance_field.h"

#include <openvdb/tree/LeafManager.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "lmk/geometry/error.h"
#include "lmk/occupancy/detail/grids.h"
#include "lmk/occupancy/detail/vdb_support.h"

namespace lmk {
namespace {

namespace vdb = openvdb;

// Voxels along x handled by one task: a whole number of leaf nodes, so that the grids built by
// different tasks never share a leaf and merge by moving nodes.
constexpr int kSlabVoxels = 8 * vdb::FloatTree::LeafNodeType::DIM;

using FloatLeaf = vdb::FloatTree::LeafNodeType;

// A direct-mapped cache from leaf origin to the leaf nodes of both grids being built.
class LeafCache {
 public:
  struct Entry {
    vdb::Coord origin{std::numeric_limits<int>::max()};
    FloatLeaf* squared = nullptr;
    float* squared_data = nullptr;
    std::int32_t* closest_data = nullptr;
  };
  LeafCache(vdb::FloatGrid::UnsafeAccessor& squared, vdb::Int32Grid::UnsafeAccessor& closest)
      : squared_(squared), closest_(closest), entries_(kSize) {}

  const Entry& leaf(const vdb::Coord& ijk) {
    const vdb::Coord origin = ijk & ~(FloatLeaf::DIM - 1);
    const unsigned hash = (static_cast<unsigned>(origin.x()) * 73856093u) ^
                          (static_cast<unsigned>(origin.y()) * 19349663u) ^
                          (static_cast<unsigned>(origin.z()) * 83492791u);
    Entry& e = entries_[(hash >> 3) & (kSize - 1)];
    if (e.origin != origin) {
      e.origin = origin;
      e.squared = squared_.touchLeaf(ijk);
      e.squared_data = e.squared->buffer().data();
      e.closest_data = closest_.touchLeaf(ijk)->buffer().data();
    }
    return e;
  }

 private:
  static constexpr unsigned kSize = 4096;
  vdb::FloatGrid::UnsafeAccessor& squared_;
  vdb::Int32Grid::UnsafeAccessor& closest_;
  std::vector<Entry> entries_;
};

struct SlabGrids {
  vdb::FloatGrid::Ptr squared;  // squared distance during the build
  vdb::Int32Grid::Ptr closest;
};

// Splats every point onto the voxel centres within the band whose x index lies in [x0, x1), keeping
// for each voxel the nearest point; ties go to the smaller index, so the result does not depend on
// the order in which slabs or points are visited.
SlabGrids build_slab(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& members,
                     double voxel, double band, int x0, int x1) {
  SlabGrids g{vdb::FloatGrid::create(static_cast<float>(band * band)), vdb::Int32Grid::create(-1)};
  // Unregistered accessors: only they modify these slab grids, which no one else sees yet.
  auto squared = g.squared->getUnsafeAccessor();
  auto closest = g.closest->getUnsafeAccessor();
  const int reach = static_cast<int>(std::ceil(band / voxel));
  // Leaf pointers are cached in a direct-mapped table: a point's neighbourhood spans a few leaves,
  // neighbouring points share them, and finding leaves through the tree dominated the build time.
  LeafCache cache(squared, closest);
  const double band_voxels2 = (band / voxel) * (band / voxel);
  for (int index : members) {
    const Eigen::Vector3d p = points[index].cast<double>() / voxel;  // in voxel units
    const Eigen::Vector3i c = p.array().round().cast<int>();
    for (int x = std::max(c.x() - reach, x0); x <= std::min(c.x() + reach, x1 - 1); ++x) {
      const double ex2 = (x - p.x()) * (x - p.x());
      for (int y = c.y() - reach; y <= c.y() + reach; ++y) {
        // The voxels of this row within the band: |z - p.z| <= sqrt(band^2 - ex^2 - ey^2).
        const double rest = band_voxels2 - ex2 - (y - p.y()) * (y - p.y());
        if (rest < 0.0) continue;
        const double half = std::sqrt(rest);
        const int z_begin = static_cast<int>(std::ceil(p.z() - half));
        const int z_end = static_cast<int>(std::floor(p.z() + half));
        const LeafCache::Entry* leaf = nullptr;
        for (int z = z_begin; z <= z_end; ++z) {
          const vdb::Coord ijk(x, y, z);
          // A row crosses a leaf boundary at most once: look the leaf up again only there.
          if (leaf == nullptr || (z & (FloatLeaf::DIM - 1)) == 0) leaf = &cache.leaf(ijk);
          float* squared_data = leaf->squared_data;
          std::int32_t* closest_data = leaf->closest_data;
          FloatLeaf* squared_leaf = leaf->squared;
          const vdb::Index offset = FloatLeaf::coordToOffset(ijk);
          const float d2 = static_cast<float>(
              (ex2 + (y - p.y()) * (y - p.y()) + (z - p.z()) * (z - p.z())) * voxel * voxel);
          // Inactive voxels hold the background, band^2, which every in-band distance matches or
          // beats.
          const float current = squared_data[offset];
          if (d2 > current ||
              (d2 == current && squared_leaf->isValueOn(offset) && index > closest_data[offset])) {
            continue;
          }
          squared_data[offset] = d2;
          closest_data[offset] = index;
          squared_leaf->setActiveState(offset, true);
        }
      }
    }
  }
  return g;
}

}  // namespace

DistanceField::DistanceField() : DistanceField({}, DistanceFieldSettings{}) {}

DistanceField::DistanceField(const std::vector<Eigen::Vector3f>& points,
                             const DistanceFieldSettings& settings) {
  const double voxel = settings.voxel_size, band = settings.band;
  if (!(voxel > 0.0 && std::isfinite(voxel))) {
    throw Error("distance field: voxel size must be positive and finite");
  }
  if (!(band >= voxel && std::isfinite(band))) {
    throw Error("distance field: the band must be finite and at least one voxel");
  }
  detail::initialize_openvdb();
  auto grids = std::make_shared<Grids>();
  grids->points = points;
  grids->band = band;

  // Bucket the points by the x slabs their band reaches.
  const int reach = static_cast<int>(std::ceil(band / voxel));
  const auto slab_of = [&](int x) {
    return static_cast<int>(std::floor(static_cast<double>(x) / kSlabVoxels));
  };
  int first = 0, last = -1;
  std::vector<std::pair<int, int>> reach_of(points.size(), {0, -1});
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) continue;
    const int cx = detail::round_to_int(points[i].x() / voxel);
    reach_of[i] = {slab_of(cx - reach), slab_of(cx + reach)};
    if (last < first) {
      first = reach_of[i].first, last = reach_of[i].second;
    } else {
      first = std::min(first, reach_of[i].first), last = std::max(last, reach_of[i].second);
    }
  }
  const int slabs = std::max(0, last - first + 1);
  std::vector<std::vector<int>> members(slabs);
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int s = reach_of[i].first; s <= reach_of[i].second; ++s) {
      members[s - first].push_back(static_cast<int>(i));
    }
  }
  std::vector<SlabGrids> parts(slabs);
  tbb::parallel_for(0, slabs, [&](int s) {
    const int x0 = (first + s) * kSlabVoxels;
    parts[s] = build_slab(points, members[s], voxel, band, x0, x0 + kSlabVoxels);
  });

  const auto transform = vdb::math::Transform::createLinearTransform(voxel);
  // The parts' background, band^2, until the square roots are taken.
  grids->distance = vdb::FloatGrid::create(static_cast<float>(band * band));
  grids->closest = vdb::Int32Grid::create(-1);
  for (SlabGrids& part : parts) {  // disjoint leaves: merging moves nodes
    grids->distance->tree().merge(part.squared->tree());
    grids->closest->tree().merge(part.closest->tree());
  }
  // Squared distances to distances, a whole leaf buffer at a time: inactive voxels hold band^2
  // and become band. Then the background and the inactive tiles above the leaves, still band^2,
  // become band too (a tile left at band^2 would read as a surface 0.4 mm away).
  vdb::tree::LeafManager<vdb::FloatTree> leaves(grids->distance->tree());
  leaves.foreach ([](FloatLeaf& leaf, std::size_t) {
    float* data = leaf.buffer().data();
    for (vdb::Index k = 0; k < FloatLeaf::SIZE; ++k) data[k] = std::sqrt(data[k]);
  });
  grids->distance->tree().root().setBackground(static_cast<float>(band), /*updateChildNodes=*/true);
  grids->distance->setTransform(transform);
  grids->closest->setTransform(transform->copy());
  grids->distance->setName("distance");
  grids->closest->setName("closest");
  grids_ = std::move(grids);
}

double DistanceField::voxel_size() const { return grids_->distance->voxelSize()[0]; }
double DistanceField::band() const { return grids_->band; }
std::size_t DistanceField::active_voxels() const {
  return static_cast<std::size_t>(grids_->distance->activeVoxelCount());
}
bool DistanceField::empty() const { return active_voxels() == 0; }
const std::vector<Eigen::Vector3f>& DistanceField::points() const { return grids_->points; }
const DistanceField::Grids& DistanceField::grids() const { return *grids_; }

DistanceField DistanceField::from_grids(std::vector<Eigen::Vector3f> points, Grids grids) {
  if (!grids.distance || !grids.closest) throw Error("distance field: missing grid");
  grids.points = std::move(points);
  DistanceField field;
  field.grids_ = std::make_shared<Grids>(std::move(grids));
  return field;
}

struct DistanceField::Sampler::Impl {
  explicit Impl(std::shared_ptr<const Grids> g)
      : grids(std::move(g)),
        distance(grids->distance->getConstUnsafeAccessor()),
        closest(grids->closest->getConstUnsafeAccessor()),
        inverse_voxel(1.0 / grids->distance->voxelSize()[0]),
        band(static_cast<float>(grids->band)) {}
  std::shared_ptr<const Grids> grids;  // a sampler keeps its grids alive
  // Unregistered accessors: the grids never change after the field is built, and registering
  // with the tree takes a lock, twice per sampler, for a few hundred lookups (the fast search makes
  // samplers per candidate).
  vdb::FloatGrid::ConstUnsafeAccessor distance;
  vdb::Int32Grid::ConstUnsafeAccessor closest;
  double inverse_voxel;
  float band;
};

DistanceField::Sampler::Sampler(const DistanceField& field)
    : impl_(std::make_unique<Impl>(field.grids_)) {}
DistanceField::Sampler::~Sampler() = default;
DistanceField::Sampler::Sampler(Sampler&&) noexcept = default;

float DistanceField::Sampler::distance(const Eigen::Vector3f& p) const {
  return distance(p, nullptr);
}

// Trilinear interpolation over the cell whose corners are the 8 voxel centres around p.
float DistanceField::Sampler::distance(const Eigen::Vector3f& p, Eigen::Vector3f* gradient) const {
  if (gradient) gradient->setZero();
  if (!p.allFinite()) return impl_->band;
  const Eigen::Vector3d q = p.cast<double>() * impl_->inverse_voxel;
  const Eigen::Vector3d base = q.array().floor();
  const Eigen::Vector3d t = q - base;
  const vdb::Coord c0(static_cast<int>(base.x()), static_cast<int>(base.y()),
                      static_cast<int>(base.z()));
  double v[2][2][2];
  bool any = false;
  // Two times in three the 8 corners lie in one leaf node: read them from its buffer directly
  // instead of through the accessor eight times.
  const vdb::Coord c1 = c0.offsetBy(1, 1, 1);
  const FloatLeaf* leaf = (c0 & ~(FloatLeaf::DIM - 1)) == (c1 & ~(FloatLeaf::DIM - 1))
                              ? impl_->distance.probeConstLeaf(c0)
                              : nullptr;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k) {
        const vdb::Coord ijk = c0.offsetBy(i, j, k);
        float value = impl_->band;
        if (leaf) {
          const vdb::Index offset = FloatLeaf::coordToOffset(ijk);
          value = leaf->getValue(offset);
          any |= leaf->isValueOn(offset);
        } else {
          any |= impl_->distance.probeValue(ijk, value);
        }
        v[i][j][k] = value;
      }
  if (!any) return impl_->band;
  // Interpolate along z, then y, then x, keeping the partial derivatives.
  double vz[2][2], dvz[2][2];
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      vz[i][j] = v[i][j][0] + t.z() * (v[i][j][1] - v[i][j][0]);
      dvz[i][j] = v[i][j][1] - v[i][j][0];
    }
  double vy[2], dvy_dz[2], dvy_dy[2];
  for (int i = 0; i < 2; ++i) {
    vy[i] = vz[i][0] + t.y() * (vz[i][1] - vz[i][0]);
    dvy_dy[i] = vz[i][1] - vz[i][0];
    dvy_dz[i] = dvz[i][0] + t.y() * (dvz[i][1] - dvz[i][0]);
  }
  const double value = vy[0] + t.x() * (vy[1] - vy[0]);
  if (gradient) {
    const Eigen::Vector3d g(vy[1] - vy[0], dvy_dy[0] + t.x() * (dvy_dy[1] - dvy_dy[0]),
                            dvy_dz[0] + t.x() * (dvy_dz[1] - dvy_dz[0]));
    *gradient = (g * impl_->inverse_voxel).cast<float>();
  }
  return static_cast<float>(value);
}

int DistanceField::Sampler::closest(const Eigen::Vector3f& p) const {
  if (!p.allFinite()) return -1;
  return impl_->closest.getValue(detail::nearest_voxel(p.cast<double>(), impl_->inverse_voxel));
}

}  // namespace lmk
