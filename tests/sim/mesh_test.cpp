// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/sim/mesh.h"

#include <gtest/gtest.h>

namespace lmk {
namespace {

// Signed volume by the divergence theorem: positive and equal to the solid's volume exactly when
// the mesh is closed and its triangles wind counter-clockwise seen from outside.
double signed_volume(const TriangleMesh& mesh) {
  double v = 0;
  for (const auto& t : mesh.triangles) {
    v += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6.0;
  }
  return v;
}

TEST(Mesh, PrimitivesAreClosedOutwardFacingAndOfTheRightVolume) {
  EXPECT_NEAR(signed_volume(make_box_mesh({0.2, 0.3, 0.4})), 0.024, 1e-12);
  const double r = 0.1, h = 0.3;
  EXPECT_NEAR(signed_volume(make_cylinder_mesh(r, h, 256)), M_PI * r * r * h,
              1e-3 * M_PI * r * r * h);
  EXPECT_NEAR(signed_volume(make_sphere_mesh(r, 128, 256)), 4.0 / 3.0 * M_PI * r * r * r,
              2e-3 * 4.0 / 3.0 * M_PI * r * r * r);
}

TEST(Mesh, LatheOfAClosedProfileIsASolidOfRevolution) {
  // A cylinder drawn as a profile from the axis, out, up and back: the same solid as the
  // primitive.
  const double r = 0.1, h = 0.3;
  const TriangleMesh lathe = make_lathe_mesh({{0, 0}, {r, 0}, {r, h}, {0, h}}, 256);
  EXPECT_NEAR(signed_volume(lathe), M_PI * r * r * h, 1e-3 * M_PI * r * r * h);
  // An open profile (a cup without its mouth) has no triangles on the missing disc.
  const TriangleMesh cup = make_lathe_mesh({{0, 0}, {r, 0}, {r, h}}, 16);
  EXPECT_EQ(cup.triangles.size(), 16u + 2u * 16u);
  for (const auto& v : cup.vertices) EXPECT_LE(v.z(), h + 1e-12);
}

TEST(Mesh, AppendTransformsTheVertices) {
  TriangleMesh mesh;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() << 1, 2, 3;
  mesh.append(make_box_mesh({1, 1, 1}));
  mesh.append(make_box_mesh({1, 1, 1}), T);
  EXPECT_EQ(mesh.triangles.size(), 24u);
  EXPECT_EQ(mesh.vertices[8], T * make_box_mesh({1, 1, 1}).vertices[0]);
  EXPECT_NEAR(signed_volume(mesh), 2.0, 1e-12);
}

}  // namespace
}  // namespace lmk
