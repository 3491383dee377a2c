// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// LeafTable: the leaf nodes of an OpenVDB tree found by arithmetic (internal/: shared within lmk
// through the distance field's grids, not installed).
//
// The fast search reads the scene's distance field some 600,000 times a search, most of them the
// closest-point lookups of ICP's correspondences. An accessor answers each by comparing the voxel
// with its cached leaf and inner nodes and, on a miss (one lookup in four: the landmark's points
// come in no spatial order), descending the tree again, out of line. A dense array of leaf
// pointers over the leaves' bounding box answers with one index and one load. Each entry keeps its
// leaf's values too, since a leaf's own reads check every time whether its buffer is still on disk
// (OpenVDB's delayed loading), an atomic load and a branch per lookup. It holds the same values the
// tree does only where the tree is leaves and background, with no tiles: the fields as
// DistanceField builds them. A tree with tiles, or whose leaves span more than kMaxEntries, gets
// no table (usable() is false) and is read through accessors.

#include <openvdb/openvdb.h>

#include <cstddef>
#include <vector>

namespace lmk::detail {

template <typename TreeT>
class LeafTable {
 public:
  using Leaf = typename TreeT::LeafNodeType;
  using Value = typename TreeT::ValueType;
  /// A leaf and its values (the buffer, in memory), or both null where the tree has no leaf.
  struct Entry {
    const Leaf* leaf = nullptr;
    const Value* values = nullptr;
  };
  /// The largest table built: 16 MB of pointers, a box of leaves 100 a side (8 m at 1 cm voxels).
  static constexpr std::size_t kMaxEntries = std::size_t{1} << 20;

  /// No table: usable() is false.
  LeafTable() = default;

  /// The table of `tree`'s leaves. `tiles_checked` says the caller knows the tree has no tiles
  /// (built from leaves alone); otherwise every tile is looked at, and any that is active or holds
  /// a value other than the background leaves the table unusable.
  LeafTable(const TreeT& tree, bool tiles_checked) {
    if (!tiles_checked && !only_background_tiles(tree)) return;
    openvdb::CoordBBox box;  // in leaf coordinates
    for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf) box.expand(leaf_coord(leaf->origin()));
    if (box.empty()) {
      usable_ = true;  // no leaves: every voxel is background
      return;
    }
    const openvdb::Coord dim = box.dim();
    const std::size_t entries = static_cast<std::size_t>(dim.x()) * dim.y() * dim.z();
    if (entries > kMaxEntries) return;
    min_ = box.min();
    size_x_ = static_cast<unsigned>(dim.x());
    size_y_ = static_cast<unsigned>(dim.y());
    size_z_ = static_cast<unsigned>(dim.z());
    leaves_.assign(entries, Entry{});
    for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf) {
      const openvdb::Coord c = leaf_coord(leaf->origin()) - min_;
      // data() loads a delayed buffer now, once, so the pointer stays valid and in memory.
      leaves_[(static_cast<std::size_t>(c.x()) * size_y_ + c.y()) * size_z_ + c.z()] = {
          &*leaf, leaf->buffer().data()};
    }
    usable_ = true;
  }

  bool usable() const { return usable_; }

  /// The leaf holding voxel `ijk`, with its values (indexed by Leaf::coordToOffset), or nulls
  /// where the tree has none (the voxel is background and inactive). Only for a usable table.
  Entry find(const openvdb::Coord& ijk) const {
    // Unsigned: coordinates below the box wrap to large values, and one comparison per axis
    // rejects both sides.
    const auto x = static_cast<unsigned>((ijk.x() >> Leaf::LOG2DIM) - min_.x());
    const auto y = static_cast<unsigned>((ijk.y() >> Leaf::LOG2DIM) - min_.y());
    const auto z = static_cast<unsigned>((ijk.z() >> Leaf::LOG2DIM) - min_.z());
    if (x >= size_x_ || y >= size_y_ || z >= size_z_) return {};
    return leaves_[(static_cast<std::size_t>(x) * size_y_ + y) * size_z_ + z];
  }

 private:
  // Arithmetic shifts: a leaf's origin is a multiple of its side, negative ones included.
  static openvdb::Coord leaf_coord(const openvdb::Coord& origin) {
    return openvdb::Coord(origin.x() >> Leaf::LOG2DIM, origin.y() >> Leaf::LOG2DIM,
                          origin.z() >> Leaf::LOG2DIM);
  }

  // Whether every value above the leaves (the root's and inner nodes' tiles) is the inactive
  // background: then a voxel outside every leaf reads as background, as the table answers.
  static bool only_background_tiles(const TreeT& tree) {
    auto value = tree.cbeginValueAll();
    value.setMaxDepth(TreeT::RootNodeType::LEVEL - 1);  // stop above the leaves' own voxels
    for (; value; ++value) {
      if (value.isValueOn() || *value != tree.background()) return false;
    }
    return true;
  }

  bool usable_ = false;
  openvdb::Coord min_;
  unsigned size_x_ = 0, size_y_ = 0, size_z_ = 0;
  std::vector<Entry> leaves_;
};

}  // namespace lmk::detail
