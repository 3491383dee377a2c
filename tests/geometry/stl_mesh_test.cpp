// SPDX-License-Identifier: BSD-3-Clause
// STL meshes (stl_mesh.h): a binary and an ASCII tetrahedron read back corner for corner, files
// that are not STL refused by name, surface points on the triangles.

#include "lmk/geometry/stl_mesh.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "lmk/geometry/error.h"

namespace lmk {
namespace {

namespace fs = std::filesystem;

// The unit tetrahedron: corners at the origin and one along each axis.
const Eigen::Vector3f kCorners[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const int kFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

fs::path temp_file(const std::string& name) {
  return fs::temp_directory_path() / ("lmk_stl_test_" + std::to_string(::getpid()) + "_" + name);
}

void write_binary(const fs::path& path) {
  std::ofstream out(path, std::ios::binary);
  char header[80] = {};
  out.write(header, sizeof(header));
  const std::uint32_t count = 4;
  out.write(reinterpret_cast<const char*>(&count), sizeof(count));
  for (const auto& f : kFaces) {
    const float normal[3] = {0, 0, 0};
    out.write(reinterpret_cast<const char*>(normal), sizeof(normal));
    for (int c : f) out.write(reinterpret_cast<const char*>(kCorners[c].data()), 3 * sizeof(float));
    const std::uint16_t attributes = 0;
    out.write(reinterpret_cast<const char*>(&attributes), sizeof(attributes));
  }
}

void write_ascii(const fs::path& path) {
  std::ofstream out(path);
  out << "solid tetra\n";
  for (const auto& f : kFaces) {
    out << " facet normal 0 0 0\n  outer loop\n";
    for (int c : f)
      out << "   vertex " << kCorners[c].x() << ' ' << kCorners[c].y() << ' ' << kCorners[c].z()
          << '\n';
    out << "  endloop\n endfacet\n";
  }
  out << "endsolid tetra\n";
}

// Every triangle of the mesh, as its three corners, is one of the tetrahedron's faces.
void expect_tetrahedron(const StlMesh& mesh) {
  ASSERT_EQ(mesh.triangles.size(), 4u);
  for (const Eigen::Vector3i& t : mesh.triangles) {
    int matched = 0;
    for (const auto& f : kFaces) {
      bool same = true;
      for (int k = 0; k < 3; ++k)
        same = same && (mesh.vertices[t[k]] - kCorners[f[k]].cast<double>()).norm() < 1e-6;
      matched += same;
    }
    EXPECT_EQ(matched, 1);
  }
}

TEST(StlMesh, BinaryAndAsciiFilesReadBackTheirTriangles) {
  const fs::path binary = temp_file("binary.stl"), ascii = temp_file("ascii.stl");
  write_binary(binary);
  write_ascii(ascii);
  expect_tetrahedron(read_stl_mesh(binary.string()));
  expect_tetrahedron(read_stl_mesh(ascii.string()));
  fs::remove(binary);
  fs::remove(ascii);
}

TEST(StlMesh, MissingAndEmptyFilesAreRefusedByName) {
  const fs::path missing = temp_file("missing.stl"), empty = temp_file("empty.stl");
  std::ofstream(empty).close();
  for (const fs::path& p : {missing, empty}) {
    try {
      read_stl_mesh(p.string());
      ADD_FAILURE() << p << " was read";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
    }
  }
  fs::remove(empty);
}

TEST(StlMesh, SurfacePointsLieOnTheScaledTriangles) {
  const fs::path binary = temp_file("surface.stl");
  write_binary(binary);
  const StlMesh mesh = read_stl_mesh(binary.string());
  fs::remove(binary);
  const Eigen::Vector3d scale(2, 1, 0.5);
  const std::vector<Eigen::Vector3d> points = mesh_surface_points(mesh, 0.05, scale);
  ASSERT_GT(points.size(), 100u);
  for (const Eigen::Vector3d& p : points) {
    // On the scaled tetrahedron's surface: on a coordinate plane or on x/2 + y + 2z = 1.
    const Eigen::Vector3d q = p.cwiseQuotient(scale);
    const double to_plane = std::min({q.x(), q.y(), q.z(), std::abs(q.sum() - 1.0)});
    EXPECT_NEAR(to_plane, 0.0, 1e-9);
    EXPECT_GE(q.minCoeff(), -1e-9);
    EXPECT_LE(q.sum(), 1.0 + 1e-9);
  }
}

}  // namespace
}  // namespace lmk
