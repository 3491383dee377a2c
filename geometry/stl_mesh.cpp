// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/stl_mesh.h"

#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSTLReader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "lmk/geometry/error.h"

namespace lmk {

// VTK's own STL reader, not PCL's loadPolygonFileSTL: PCL 1.13's conversion from VTK frees an array
// it took from malloc with operator delete, which AddressSanitizer rightly refuses.
StlMesh read_stl_mesh(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error("mesh '" + path + "': no such file (a <collision> mesh of the robot description)");
  vtkNew<vtkSTLReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* data = reader->GetOutput();
  if (reader->GetErrorCode() != 0 || data == nullptr || data->GetNumberOfPolys() == 0)
    throw Error("mesh '" + path + "': not a readable STL file with triangles");
  StlMesh mesh;
  const vtkIdType n = data->GetNumberOfPoints();
  mesh.vertices.reserve(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i) {
    double p[3];
    data->GetPoint(i, p);
    mesh.vertices.emplace_back(p[0], p[1], p[2]);
  }
  vtkCellArray* polys = data->GetPolys();
  vtkNew<vtkIdList> corners;
  for (polys->InitTraversal(); polys->GetNextCell(corners);) {
    // A polygon of more than three corners is fanned into triangles from its first.
    for (vtkIdType k = 2; k < corners->GetNumberOfIds(); ++k) {
      const Eigen::Vector3i t(static_cast<int>(corners->GetId(0)),
                              static_cast<int>(corners->GetId(k - 1)),
                              static_cast<int>(corners->GetId(k)));
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
