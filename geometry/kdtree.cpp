// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/kdtree.h"

#include <nanoflann.hpp>

#include "lmk/geometry/error.h"

namespace lmk {

// nanoflann's dataset adaptor: the tree reads coordinates through these three calls.
struct KdTree::Impl {
  std::vector<Eigen::Vector3f> points;  // finite points only
  Indices source_index;                 // points[i] is cloud.points[source_index[i]]

  std::size_t kdtree_get_point_count() const { return points.size(); }
  float kdtree_get_pt(std::size_t i, std::size_t dim) const { return points[i][dim]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const {
    return false;  // let nanoflann compute the bounding box
  }

  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Impl>, Impl,
                                                   3, Index>;
  std::unique_ptr<Tree> tree;
};

KdTree::KdTree(const PointCloud& cloud, int leaf_max_size) : impl_(std::make_unique<Impl>()) {
  if (leaf_max_size < 1) throw Error("KdTree: leaf_max_size must be at least 1");
  impl_->points.reserve(cloud.size());
  impl_->source_index.reserve(cloud.size());
  for (Index i = 0; i < cloud.size(); ++i) {
    if (!is_finite(cloud.points[i])) continue;
    impl_->points.push_back(cloud.points[i]);
    impl_->source_index.push_back(i);
  }
  // The tree keeps a reference to *impl_, which lives on the heap and so survives moves of KdTree.
  impl_->tree = std::make_unique<Impl::Tree>(
      3, *impl_,
      nanoflann::KDTreeSingleIndexAdaptorParams(static_cast<std::size_t>(leaf_max_size)));
}

KdTree::~KdTree() = default;
KdTree::KdTree(KdTree&&) noexcept = default;
KdTree& KdTree::operator=(KdTree&&) noexcept = default;

std::size_t KdTree::size() const { return impl_->points.size(); }

void KdTree::knn(const Eigen::Vector3f& query, std::size_t k, std::vector<Neighbor>& out) const {
  out.clear();
  if (k == 0 || impl_->points.empty()) return;
  // Scratch for nanoflann's result arrays: on the stack for the usual small k, so that repeated
  // queries into a reused `out` allocate nothing.
  constexpr std::size_t kStackK = 32;
  Index idx_stack[kStackK];
  float d2_stack[kStackK];
  std::vector<Index> idx_heap;
  std::vector<float> d2_heap;
  Index* idx = idx_stack;
  float* d2 = d2_stack;
  if (k > kStackK) {
    idx_heap.resize(k);
    d2_heap.resize(k);
    idx = idx_heap.data();
    d2 = d2_heap.data();
  }
  const std::size_t found = impl_->tree->knnSearch(query.data(), k, idx, d2);
  out.resize(found);
  for (std::size_t i = 0; i < found; ++i) out[i] = {impl_->source_index[idx[i]], d2[i]};
}

std::vector<Neighbor> KdTree::knn(const Eigen::Vector3f& query, std::size_t k) const {
  std::vector<Neighbor> out;
  knn(query, k, out);
  return out;
}

std::optional<Neighbor> KdTree::nearest(const Eigen::Vector3f& query) const {
  if (impl_->points.empty()) return std::nullopt;
  Index idx = 0;
  float d2 = 0.0f;
  impl_->tree->knnSearch(query.data(), 1, &idx, &d2);
  return Neighbor{impl_->source_index[idx], d2};
}

std::vector<Neighbor> KdTree::radius(const Eigen::Vector3f& query, float radius) const {
  std::vector<Neighbor> out;
  radius_search(query, radius, /*sorted=*/true, out);
  return out;
}

void KdTree::radius_unsorted(const Eigen::Vector3f& query, float radius,
                             std::vector<Neighbor>& out) const {
  radius_search(query, radius, /*sorted=*/false, out);
}

void KdTree::radius_search(const Eigen::Vector3f& query, float radius, bool sorted,
                           std::vector<Neighbor>& out) const {
  out.clear();
  if (!(radius >= 0.0f) || impl_->points.empty()) return;
  // nanoflann's L2_Simple metric works in squared distances. Its result buffer is kept per thread:
  // the fast search asks a thousand radius queries of a thousand neighbours each per search.
  thread_local std::vector<std::pair<Index, float>> matches;
  matches.clear();
  impl_->tree->radiusSearch(query.data(), radius * radius, matches,
                            nanoflann::SearchParams(32, 0.0f, sorted));
  out.reserve(matches.size());
  for (const auto& [i, d2] : matches) out.push_back({impl_->source_index[i], d2});
}

}  // namespace lmk
