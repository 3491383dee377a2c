// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Reading a triangle mesh from an STL file (binary or ASCII, with VTK's reader), as a
// robot description's collision meshes come (issue #60), and spreading points over its surface.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace lmk {

struct StlMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;  ///< indices into vertices
};

/// Reads `path`; throws lmk::Error naming it when it is missing, unreadable or holds no triangle.
StlMesh read_stl_mesh(const std::string& path);

/// The mesh's vertices and points spread over each triangle, no two neighbours farther apart than
/// about `spacing` (> 0), each scaled by `scale` per axis (a URDF mesh's scale attribute).
std::vector<Eigen::Vector3d> mesh_surface_points(const StlMesh& mesh, double spacing,
                                                 const Eigen::Vector3d& scale = {1, 1, 1});

}  // namespace lmk
