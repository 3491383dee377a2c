// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/occupancy/distance_field.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <sstream>

#include "lmk/geometry/error.h"
#include "lmk/geometry/internal/voxel_key.h"
#include "lmk/geometry/internal/voxel_table.h"
#include "lmk/occupancy/detail/vdb_support.h"
#include "lmk/occupancy/internal/grids.h"

namespace lmk {
namespace {

namespace vdb = openvdb;

// Voxels along x handled by one task: a whole number of leaf nodes, so that the leaves built by
// different tasks never overlap and go into the grids as they are.
constexpr int kSlabVoxels = 8 * vdb::FloatTree::LeafNodeType::DIM;

using FloatLeaf = vdb::FloatTree::LeafNodeType;
using IndexLeaf = vdb::Int32Tree::LeafNodeType;
constexpr int kLeafLog2 = static_cast<int>(FloatLeaf::LOG2DIM);
constexpr int kLeafMask = static_cast<int>(FloatLeaf::DIM) - 1;

// Leaf coordinates (voxel >> 3) are packed into voxel keys, 21 bits an axis: points farther than
// this many voxels from the origin along an axis are refused rather than wrapped.
constexpr double kMaxVoxelCoordinate =
    static_cast<double>(detail::kVoxelKeyOffset - 1) * FloatLeaf::DIM;

// One leaf of a slab while it is built: a plain array, indexed as OpenVDB indexes a leaf, so that
// the splat's inner loop reads and writes memory without a tree in between. Each voxel holds its
// nearest point so far as one key, the squared distance's bits above the point's index: squared
// distances are never negative, and the bits of non-negative floats order as the floats do, so the
// smaller key is the nearer point, the smaller index on a tie. The update is then an integer
// minimum, which compiles without branches (the float comparisons of distance and index did not,
// and mispredicted).
struct LeafBlock {
  static constexpr std::int32_t kUnclaimed = std::numeric_limits<std::int32_t>::max();
  static std::uint64_t key(float squared, std::int32_t index) {
    std::uint32_t bits;
    std::memcpy(&bits, &squared, sizeof bits);
    return (std::uint64_t{bits} << 32) | static_cast<std::uint32_t>(index);
  }
  static float squared_of(std::uint64_t key) {
    const auto bits = static_cast<std::uint32_t>(key >> 32);
    float squared;
    std::memcpy(&squared, &bits, sizeof squared);
    return squared;
  }
  static std::int32_t index_of(std::uint64_t key) {
    return static_cast<std::int32_t>(key & 0xffffffffu);
  }
  vdb::Coord origin;
  std::array<std::uint64_t, FloatLeaf::SIZE> nearest;
};

// The leaf blocks of one slab, found by leaf coordinate.
class SlabBlocks {
 public:
  SlabBlocks(std::size_t expected_points, float background)
      : table_(expected_points / 16 + 16), background_(background) {}

  LeafBlock* at(int lx, int ly, int lz) {
    const std::uint32_t id = table_.insert(detail::pack_voxel({lx, ly, lz}));
    if (id == blocks_.size()) {
      auto block = std::make_unique<LeafBlock>();
      // Leaf coordinates times the leaf's side (a left shift of a negative one is undefined).
      constexpr int kSide = static_cast<int>(FloatLeaf::DIM);
      block->origin = vdb::Coord(lx * kSide, ly * kSide, lz * kSide);
      block->nearest.fill(LeafBlock::key(background_, LeafBlock::kUnclaimed));
      blocks_.push_back(std::move(block));
    }
    return blocks_[id].get();
  }
  const std::vector<std::unique_ptr<LeafBlock>>& blocks() const { return blocks_; }

 private:
  detail::VoxelTable table_;
  float background_;
  std::vector<std::unique_ptr<LeafBlock>> blocks_;
};

// A slab's leaves as OpenVDB leaf nodes: distances (square roots taken) active where a point
// claimed the voxel, and the closest-point indices, -1 elsewhere.
struct SlabLeaves {
  std::vector<std::unique_ptr<FloatLeaf>> distance;
  std::vector<std::unique_ptr<IndexLeaf>> closest;
};

// Splats every point onto the voxel centres within the band whose x index lies in [x0, x1), keeping
// for each voxel the nearest point; ties go to the smaller index, so the result does not depend on
// the order in which slabs or points are visited.
// Every member point splatted into `blocks`: each voxel within the band of it, in slab columns
// [x0, x1), keeps the nearest point.
void splat_points(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& members,
                  double voxel, double band, int x0, int x1, const StopCheck& stop,
                  SlabBlocks& blocks) {
  const int reach = static_cast<int>(std::ceil(band / voxel));
  const double band_voxels2 = (band / voxel) * (band / voxel);
  // The leaves a point's box of 2 reach + 1 voxels a side can touch, per axis; the point's leaves
  // are looked up once, not once per row (the lookups dominated the build time).
  const int span = 2 * reach / static_cast<int>(FloatLeaf::DIM) + 2;
  std::vector<LeafBlock*> near(static_cast<std::size_t>(span * span * span));
  // The leaves of the last point's box: the next point's box, a voxel or two away, usually lies in
  // the same ones, and then keeps them without looking them up again.
  Eigen::Vector3i near_leaf0(0, 0, 0), near_leaves(0, 0, 0);
  // What a column z of the point's box contributes to each of its rows, worked out once per point
  // rather than once per row: the squared offset, the leaf among the row's, the voxel's place in
  // the leaf along z.
  const int columns = 2 * reach + 1;  // z is not clipped to the slab: every point has them all
  std::vector<double> column_ez2(static_cast<std::size_t>(columns));
  std::vector<int> column_leaf(column_ez2.size()), column_offset(column_ez2.size());
  // A point splats up to (2 reach + 1)^3 voxels: checked more often than a plain point loop.
  for (std::size_t m = 0; m < members.size(); ++m) {
    if (stop && m % (kItemsPerStopCheck / 16) == 0) stop();
    const int index = members[m];
    const Eigen::Vector3d p = points[index].cast<double>() / voxel;  // in voxel units
    // The voxel nearest the point, halves rounded up (std::round's away from zero was a libm call
    // per axis): either rounding's box holds every voxel within the band of a point at a half.
    const Eigen::Vector3i c(detail::round_to_int(p.x()), detail::round_to_int(p.y()),
                            detail::round_to_int(p.z()));
    const Eigen::Vector3i first(std::max(c.x() - reach, x0), c.y() - reach, c.z() - reach);
    const Eigen::Vector3i last(std::min(c.x() + reach, x1 - 1), c.y() + reach, c.z() + reach);
    const Eigen::Vector3i leaf0 = first.unaryExpr([](int v) { return v >> kLeafLog2; });
    const Eigen::Vector3i leaves =
        last.unaryExpr([](int v) { return v >> kLeafLog2; }) - leaf0 + Eigen::Vector3i::Ones();
    if (leaf0 != near_leaf0 || leaves != near_leaves) {
      for (int i = 0; i < leaves.x(); ++i) {
        for (int j = 0; j < leaves.y(); ++j) {
          for (int k = 0; k < leaves.z(); ++k) {
            near[(i * span + j) * span + k] =
                blocks.at(leaf0.x() + i, leaf0.y() + j, leaf0.z() + k);
          }
        }
      }
      near_leaf0 = leaf0, near_leaves = leaves;
    }
    for (int k = 0; k < columns; ++k) {
      const int z = first.z() + k;
      column_ez2[k] = (z - p.z()) * (z - p.z());
      column_leaf[k] = (z >> kLeafLog2) - leaf0.z();
      column_offset[k] = z & kLeafMask;
    }
    for (int x = first.x(); x <= last.x(); ++x) {
      const double ex2 = (x - p.x()) * (x - p.x());
      for (int y = first.y(); y <= last.y(); ++y) {
        const double ey2 = (y - p.y()) * (y - p.y());
        const double rest = band_voxels2 - ex2 - ey2;  // the row lies within the band where >= 0
        if (rest < 0.0) continue;
        LeafBlock* const* row =
            &near[(((x >> kLeafLog2) - leaf0.x()) * span + (y >> kLeafLog2) - leaf0.y()) * span];
        const int row_offset =
            ((x & kLeafMask) << (2 * kLeafLog2)) | ((y & kLeafMask) << kLeafLog2);
        // The row's columns within the band, if any: ez2 falls, then rises along the row
        // (rounding keeps the order of |z - p.z|), so they are one run, found from its two ends.
        // (Masking the update instead cost a full row for the band's few voxels near its rim.)
        int k0 = 0, k1 = columns - 1;
        while (k0 <= k1 && column_ez2[k0] > rest) ++k0;
        while (k1 >= k0 && column_ez2[k1] > rest) --k1;
        for (int k = k0; k <= k1; ++k) {
          LeafBlock& b = *row[column_leaf[k]];
          const int offset = row_offset | column_offset[k];
          const auto d2 = static_cast<float>((ex2 + ey2 + column_ez2[k]) * voxel * voxel);
          b.nearest[offset] = std::min(b.nearest[offset], LeafBlock::key(d2, index));
        }
      }
    }
  }
}

// The blocks as OpenVDB leaves: the distance (the square root of the nearest squared distance)
// and the closest point's index, active where a point claimed the voxel. Blocks whose box corner
// no point reached stay out of the grids.
SlabLeaves leaves_of(const SlabBlocks& blocks, float background, const StopCheck& stop) {
  SlabLeaves out;
  const float outside = std::sqrt(background);  // what the square-root pass made of band^2
  std::size_t converted = 0;
  for (const auto& block : blocks.blocks()) {
    if (stop && ++converted % 1024 == 0) stop();
    if (std::all_of(block->nearest.begin(), block->nearest.end(), [](std::uint64_t k) {
          return LeafBlock::index_of(k) == LeafBlock::kUnclaimed;
        })) {
      continue;
    }
    auto distance = std::make_unique<FloatLeaf>(block->origin, outside);
    auto closest = std::make_unique<IndexLeaf>(block->origin, -1);
    float* distance_data = distance->buffer().data();
    std::int32_t* closest_data = closest->buffer().data();
    for (vdb::Index k = 0; k < FloatLeaf::SIZE; ++k) {
      const std::int32_t closest_index = LeafBlock::index_of(block->nearest[k]);
      if (closest_index == LeafBlock::kUnclaimed) continue;
      distance_data[k] = std::sqrt(LeafBlock::squared_of(block->nearest[k]));
      distance->setActiveState(k, true);
      closest_data[k] = closest_index;
    }
    out.distance.push_back(std::move(distance));
    out.closest.push_back(std::move(closest));
  }
  return out;
}

SlabLeaves build_slab(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& members,
                      double voxel, double band, int x0, int x1, const StopCheck& stop) {
  const auto background = static_cast<float>(band * band);
  SlabBlocks blocks(members.size(), background);
  splat_points(points, members, voxel, band, x0, x1, stop, blocks);
  return leaves_of(blocks, background, stop);
}

}  // namespace

DistanceField::DistanceField() : DistanceField({}, DistanceFieldSettings{}) {}

DistanceField::DistanceField(const std::vector<Eigen::Vector3f>& points,
                             const DistanceFieldSettings& settings, const StopCheck& stop) {
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
  const auto slab_of = [&](int x) {  // floor(x / kSlabVoxels) in integers, negatives included
    return x >= 0 ? x / kSlabVoxels : -((-x + kSlabVoxels - 1) / kSlabVoxels);
  };
  const double limit = (kMaxVoxelCoordinate - reach) * voxel;
  int first = 0, last = -1;
  std::vector<std::pair<int, int>> reach_of(points.size(), {0, -1});
  for (std::size_t i = 0; i < points.size(); ++i) {
    check_every(stop, i);
    if (!points[i].allFinite()) continue;
    if (points[i].cast<double>().cwiseAbs().maxCoeff() > limit) {
      std::ostringstream message;
      message << "distance field: a point lies more than " << limit
              << " m from the origin along an axis, beyond what voxels of " << voxel
              << " m can index; crop the cloud";
      throw Error(message.str());
    }
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
    check_every(stop, i);
    for (int s = reach_of[i].first; s <= reach_of[i].second; ++s) {
      members[s - first].push_back(static_cast<int>(i));
    }
  }
  std::vector<SlabLeaves> parts(slabs);
  tbb::parallel_for(0, slabs, [&](int s) {
    const int x0 = (first + s) * kSlabVoxels;
    parts[s] = build_slab(points, members[s], voxel, band, x0, x0 + kSlabVoxels, stop);
  });

  const auto transform = vdb::math::Transform::createLinearTransform(voxel);
  // The leaves' inactive voxels hold sqrt(band^2), what the square-root pass made of it; the
  // background is the band, and so are the inactive tiles above the leaves, which take the
  // background as the leaves go in (a tile at band^2 would read as a surface 0.4 mm away). Set
  // before the leaves rather than after: resetting it afterwards visits every leaf's voxels.
  grids->distance = vdb::FloatGrid::create(static_cast<float>(band));
  grids->closest = vdb::Int32Grid::create(-1);
  for (SlabLeaves& part : parts) {  // the slabs' leaves are disjoint
    for (auto& leaf : part.distance) grids->distance->tree().addLeaf(leaf.release());
    for (auto& leaf : part.closest) grids->closest->tree().addLeaf(leaf.release());
  }
  grids->distance->setTransform(transform);
  grids->closest->setTransform(transform->copy());
  grids->distance->setName("distance");
  grids->closest->setName("closest");
  // Leaves only, as added above: no tile to look for.
  grids->distance_leaves = detail::LeafTable<vdb::FloatTree>(grids->distance->tree(), true);
  grids->closest_leaves = detail::LeafTable<vdb::Int32Tree>(grids->closest->tree(), true);
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
  // Stored grids may hold tiles: the tables check, and stay unused where they find one.
  grids.distance_leaves = detail::LeafTable<vdb::FloatTree>(grids.distance->tree(), false);
  grids.closest_leaves = detail::LeafTable<vdb::Int32Tree>(grids.closest->tree(), false);
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

  // The closest point's index at `voxel`: from the leaf table where the grid has one (the fields
  // DistanceField builds), else through the accessor.
  int closest_at(const vdb::Coord& voxel) {
    if (!grids->closest_leaves.usable()) return closest.getValue(voxel);
    const auto found = grids->closest_leaves.find(voxel);
    return found.values ? found.values[IndexLeaf::coordToOffset(voxel)] : -1;
  }
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
  // instead of looking each up.
  const vdb::Coord c1 = c0.offsetBy(1, 1, 1);
  const bool one_leaf = (c0 & ~(FloatLeaf::DIM - 1)) == (c1 & ~(FloatLeaf::DIM - 1));
  using Table = detail::LeafTable<vdb::FloatTree>;
  const Table& table = impl_->grids->distance_leaves;
  Table::Entry leaf;
  if (one_leaf) {
    if (table.usable()) {
      leaf = table.find(c0);
      if (!leaf.leaf) return impl_->band;  // no tiles: a cell outside every leaf is background
    } else if ((leaf.leaf = impl_->distance.probeConstLeaf(c0))) {
      leaf.values = leaf.leaf->buffer().data();
    }
  }
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k) {
        const vdb::Coord ijk = c0.offsetBy(i, j, k);
        const Table::Entry corner = one_leaf || !table.usable() ? leaf : table.find(ijk);
        float value = impl_->band;
        if (corner.leaf) {
          const vdb::Index offset = FloatLeaf::coordToOffset(ijk);
          value = corner.values[offset];
          any |= corner.leaf->isValueOn(offset);
        } else if (!table.usable()) {
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
  return impl_->closest_at(detail::nearest_voxel(p.cast<double>(), impl_->inverse_voxel));
}

void DistanceField::Sampler::closest(const std::vector<Eigen::Vector3f>& points,
                                     std::vector<int>& indices) const {
  indices.resize(points.size());
  Impl& impl = *impl_;
  const double inverse_voxel = impl.inverse_voxel;
  for (std::size_t k = 0; k < points.size(); ++k) {
    indices[k] =
        points[k].allFinite()
            ? impl.closest_at(detail::nearest_voxel(points[k].cast<double>(), inverse_voxel))
            : -1;
  }
}

}  // namespace lmk
