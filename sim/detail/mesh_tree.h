// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A CGAL AABB tree over a TriangleMesh, shared by the depth sensor's ray casting and the
// distance queries of the ground-truth checks. Internal.

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <vector>

#include "lmk/sim/mesh.h"

namespace lmk::detail {

using Kernel = CGAL::Simple_cartesian<double>;
using Triangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

inline Kernel::Point_3 to_cgal(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

/// The mesh's triangles and their tree, built before any query so that parallel queries only
/// read it. The tree refers to `triangles`, so the struct must not be copied.
struct MeshTree {
  explicit MeshTree(const TriangleMesh& mesh) {
    triangles.reserve(mesh.triangles.size());
    for (const Eigen::Vector3i& t : mesh.triangles) {
      triangles.emplace_back(to_cgal(mesh.vertices[t[0]]), to_cgal(mesh.vertices[t[1]]),
                             to_cgal(mesh.vertices[t[2]]));
    }
    tree.insert(triangles.begin(), triangles.end());
    tree.build();
  }
  MeshTree(const MeshTree&) = delete;
  MeshTree& operator=(const MeshTree&) = delete;

  std::vector<Triangle> triangles;
  AabbTree tree;
};

}  // namespace lmk::detail
