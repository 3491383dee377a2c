// SPDX-License-Identifier: BSD-3-Clause
#include <tbb/parallel_for.h>

#include <cmath>

#include "lmk/geometry/error.h"
#include "lmk/sim/detail/mesh_tree.h"
#include "lmk/sim/mesh.h"

namespace lmk {

std::vector<double> distances_to_mesh(const TriangleMesh& mesh,
                                      const std::vector<Eigen::Vector3d>& points) {
  if (mesh.triangles.empty()) throw Error("distances_to_mesh: the mesh has no triangle");
  detail::MeshTree tree(mesh);
  tree.tree.accelerate_distance_queries();  // before the parallel queries, which only read
  std::vector<double> out(points.size());
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) {
    out[i] = std::sqrt(tree.tree.squared_distance(detail::to_cgal(points[i])));
  });
  return out;
}

}  // namespace lmk
