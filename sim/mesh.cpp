// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/sim/mesh.h"

#include <cmath>

namespace lmk {

void TriangleMesh::append(const TriangleMesh& other, const Eigen::Isometry3d& T_this_other) {
  const int base = static_cast<int>(vertices.size());
  if (colours.empty() && !other.colours.empty()) colours.assign(triangles.size(), kUnpainted);
  if (!colours.empty()) {
    if (other.colours.empty()) {
      colours.insert(colours.end(), other.triangles.size(), kUnpainted);
    } else {
      colours.insert(colours.end(), other.colours.begin(), other.colours.end());
    }
  }
  for (const Eigen::Vector3d& v : other.vertices) vertices.push_back(T_this_other * v);
  for (const Eigen::Vector3i& t : other.triangles) triangles.push_back(t.array() + base);
}

TriangleMesh painted(TriangleMesh mesh, const Color& colour) {
  mesh.colours.assign(mesh.triangles.size(), colour);
  return mesh;
}

TriangleMesh make_box_mesh(const Eigen::Vector3d& size) {
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d sign((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
    mesh.vertices.push_back(0.5 * sign.cwiseProduct(size));
  }
  // Two triangles per face; corner i has bit 0 = +x, bit 1 = +y, bit 2 = +z.
  mesh.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6},   // -z, +z
                    {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},   // -y, +y
                    {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};  // -x, +x
  return mesh;
}

TriangleMesh make_cylinder_mesh(double radius, double height, int segments) {
  TriangleMesh mesh;
  const double h = 0.5 * height;
  for (int i = 0; i < segments; ++i) {
    const double a = 2.0 * M_PI * i / segments;
    mesh.vertices.emplace_back(radius * std::cos(a), radius * std::sin(a), -h);
    mesh.vertices.emplace_back(radius * std::cos(a), radius * std::sin(a), h);
  }
  const int bottom = static_cast<int>(mesh.vertices.size());
  mesh.vertices.emplace_back(0, 0, -h);
  mesh.vertices.emplace_back(0, 0, h);
  for (int i = 0; i < segments; ++i) {
    const int j = (i + 1) % segments;
    mesh.triangles.emplace_back(2 * i, 2 * j, 2 * j + 1);
    mesh.triangles.emplace_back(2 * i, 2 * j + 1, 2 * i + 1);
    mesh.triangles.emplace_back(bottom, 2 * j, 2 * i);
    mesh.triangles.emplace_back(bottom + 1, 2 * i + 1, 2 * j + 1);
  }
  return mesh;
}

TriangleMesh make_lathe_mesh(const std::vector<Eigen::Vector2d>& profile, int segments) {
  TriangleMesh mesh;
  for (const Eigen::Vector2d& p : profile) {
    for (int s = 0; s < segments; ++s) {
      const double a = 2.0 * M_PI * s / segments;
      mesh.vertices.emplace_back(p.x() * std::cos(a), p.x() * std::sin(a), p.y());
    }
  }
  for (std::size_t r = 0; r + 1 < profile.size(); ++r) {
    for (int s = 0; s < segments; ++s) {
      const int a = static_cast<int>(r) * segments + s;
      const int b = static_cast<int>(r) * segments + (s + 1) % segments;
      const int c = a + segments, d = b + segments;
      // A ring on the axis collapses its quads to triangles: drop the degenerate half.
      if (profile[r].x() > 0.0) mesh.triangles.emplace_back(a, b, d);
      if (profile[r + 1].x() > 0.0) mesh.triangles.emplace_back(a, d, c);
    }
  }
  return mesh;
}

TriangleMesh make_sphere_mesh(double radius, int rings, int segments) {
  TriangleMesh mesh;
  for (int r = 0; r <= rings; ++r) {
    const double polar = M_PI * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double azimuth = 2.0 * M_PI * s / segments;
      mesh.vertices.emplace_back(radius * std::sin(polar) * std::cos(azimuth),
                                 radius * std::sin(polar) * std::sin(azimuth),
                                 radius * std::cos(polar));
    }
  }
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const int a = r * segments + s, b = r * segments + (s + 1) % segments;
      const int c = a + segments, d = b + segments;
      mesh.triangles.emplace_back(a, c, d);
      mesh.triangles.emplace_back(a, d, b);
    }
  }
  return mesh;
}

}  // namespace lmk
