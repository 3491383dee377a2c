// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/stl_mesh.h"

#include <pcl/PolygonMesh.h>
#include <pcl/conversions.h>
#include <pcl/io/vtk_lib_io.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "lmk/geometry/error.h"

namespace lmk {

StlMesh read_stl_mesh(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error("mesh '" + path + "': no such file (a <collision> mesh of the robot description)");
  pcl::PolygonMesh polygons;
  if (pcl::io::loadPolygonFileSTL(path, polygons) == 0 || polygons.polygons.empty())
    throw Error("mesh '" + path + "': not a readable STL file with triangles");
  pcl::PointCloud<pcl::PointXYZ> cloud;
  pcl::fromPCLPointCloud2(polygons.cloud, cloud);
  StlMesh mesh;
  mesh.vertices.reserve(cloud.size());
  for (const pcl::PointXYZ& p : cloud.points) mesh.vertices.emplace_back(p.x, p.y, p.z);
  const int n = static_cast<int>(mesh.vertices.size());
  for (const pcl::Vertices& v : polygons.polygons) {
    // A polygon of more than three corners is fanned into triangles from its first.
    for (std::size_t k = 2; k < v.vertices.size(); ++k) {
      const Eigen::Vector3i t(static_cast<int>(v.vertices[0]), static_cast<int>(v.vertices[k - 1]),
                              static_cast<int>(v.vertices[k]));
      if ((t.array() >= 0).all() && (t.array() < n).all()) mesh.triangles.push_back(t);
    }
  }
  if (mesh.triangles.empty()) throw Error("mesh '" + path + "': holds no triangle");
  return mesh;
}

std::vector<Eigen::Vector3d> mesh_surface_points(const StlMesh& mesh, double spacing,
                                                 const Eigen::Vector3d& scale) {
  if (!(spacing > 0.0)) throw Error("mesh surface points: the spacing must be positive");
  std::vector<Eigen::Vector3d> out;
  for (const Eigen::Vector3d& v : mesh.vertices) out.push_back(v.cwiseProduct(scale));
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]].cwiseProduct(scale),
                          b = mesh.vertices[t[1]].cwiseProduct(scale),
                          c = mesh.vertices[t[2]].cwiseProduct(scale);
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int n = static_cast<int>(std::ceil(longest / spacing));
    if (n <= 1) continue;  // its corners are close enough
    // A barycentric grid of n steps along each edge.
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        const double u = static_cast<double>(i) / n, w = static_cast<double>(j) / n;
        out.push_back(a + u * (b - a) + w * (c - a));
      }
    }
  }
  return out;
}

}  // namespace lmk
