// SPDX-License-Identifier: BSD-3-Clause
#include <gtest/gtest.h>

#include <filesystem>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/random.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

// A 20 x 15 organised cloud with NaN holes, normals, colours (with alpha), labels and a sensor
// pose.
PointCloud rich_cloud(bool with_alpha) {
  PointCloud cloud = test::random_cloud(300, 99);
  cloud.width = 20;
  cloud.height = 15;
  SplitMix64 rng(100);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    cloud.normals.push_back(
        Eigen::Vector3d(rng.normal(), rng.normal(), rng.normal()).normalized().cast<float>());
    cloud.colors.push_back(
        {static_cast<std::uint8_t>(rng.uniform_index(256)),
         static_cast<std::uint8_t>(rng.uniform_index(256)),
         static_cast<std::uint8_t>(rng.uniform_index(256)),
         with_alpha ? static_cast<std::uint8_t>(rng.uniform_index(256)) : std::uint8_t{255}});
    cloud.labels.push_back(static_cast<std::int32_t>(rng.uniform_index(40)));
  }
  for (std::size_t i = 0; i < cloud.size(); i += 7)
    cloud.points[i] = Eigen::Vector3f::Constant(std::nanf(""));
  cloud.T_cloud_sensor = pose_from_xyz_rpy({0.1, -0.2, 1.5}, {0.2, -0.3, 0.4});
  return cloud;
}

void expect_points_equal(const PointCloud& a, const PointCloud& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!is_finite(a.points[i])) {
      EXPECT_FALSE(is_finite(b.points[i])) << i;
    } else {
      EXPECT_EQ(a.points[i], b.points[i])
          << i;  // bit-exact: every format keeps full float precision
    }
  }
}

struct Case {
  std::string extension;
  Encoding encoding;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.extension << " " << to_string(c.encoding);
}

class RoundTrip : public ::testing::TestWithParam<Case> {};

TEST_P(RoundTrip, KeepsPointsAttributesOrganisationAndSensor) {
  const Case c = GetParam();
  for (const bool alpha : {false, true}) {
    test::ScratchDir dir;
    const PointCloud original = rich_cloud(alpha);
    const std::string path = dir.file("cloud" + c.extension);
    write_cloud(path, original, {c.encoding});
    const CloudFile file = read_cloud_file(path);
    const PointCloud& back = file.cloud;
    EXPECT_EQ(file.encoding, c.encoding == Encoding::kBinaryCompressed && c.extension == ".ply"
                                 ? Encoding::kBinary
                                 : c.encoding);
    expect_points_equal(original, back);
    EXPECT_EQ(back.width, original.width);
    EXPECT_EQ(back.height, original.height);
    EXPECT_EQ(back.normals.size(), original.size());
    for (std::size_t i = 0; i < original.size(); ++i) {
      EXPECT_EQ(back.normals[i], original.normals[i]);
    }
    EXPECT_EQ(back.colors, original.colors);
    EXPECT_EQ(back.labels, original.labels);
    EXPECT_TRUE(back.T_cloud_sensor.isApprox(original.T_cloud_sensor, 1e-6));
    // Nothing but the target is left in the directory: the temporary file was renamed.
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllFormats, RoundTrip,
    ::testing::Values(Case{".pcd", Encoding::kAscii}, Case{".pcd", Encoding::kBinary},
                      Case{".pcd", Encoding::kBinaryCompressed}, Case{".ply", Encoding::kAscii},
                      Case{".ply", Encoding::kBinary}),
    [](const auto& info) {
      return info.param.extension.substr(1) + "_" + to_string(info.param.encoding);
    });

TEST(RoundTripXyz, KeepsCoordinatesIncludingNaN) {
  test::ScratchDir dir;
  const PointCloud original = rich_cloud(false);
  write_cloud(dir.file("cloud.xyz"), original);
  const PointCloud back = read_cloud(dir.file("cloud.xyz"));
  expect_points_equal(original, back);
  EXPECT_FALSE(back.is_organized());
  EXPECT_FALSE(back.has_normals());
}

TEST(Write, IsAtomicAndReplacesTheOldFile) {
  test::ScratchDir dir;
  const std::string path = dir.file("cloud.pcd");
  write_cloud(path, test::random_cloud(10, 1));
  write_cloud(path, test::random_cloud(20, 2));
  EXPECT_EQ(read_cloud(path).size(), 20u);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);
}

TEST(Write, BadTargetsAreErrorsAndLeaveNothingBehind) {
  test::ScratchDir dir;
  EXPECT_THROW(write_cloud(dir.file("cloud.obj"), test::random_cloud(5, 1)), Error);
  EXPECT_THROW(write_cloud(dir.file("missing/cloud.pcd"), test::random_cloud(5, 1)), Error);
  PointCloud inconsistent = test::random_cloud(5, 1);
  inconsistent.labels = {1, 2};
  EXPECT_THROW(write_cloud(dir.file("cloud.pcd"), inconsistent), Error);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 0);
}

TEST(Read, PaddingAndDoubleFieldsAndUintColour) {
  test::ScratchDir dir;
  const std::string path = dir.file("padded.pcd");
  test::write_text(path,
                   "VERSION 0.7\nFIELDS x y z _ rgba label\nSIZE 8 8 8 1 4 4\nTYPE F F F U U U\n"
                   "COUNT 1 1 1 3 1 1\nWIDTH 2\nHEIGHT 1\nVIEWPOINT 1 2 3 1 0 0 0\nPOINTS 2\n"
                   "DATA ascii\n0.5 1.5 2.5 0 0 0 4278255360 7\n-1 -2 -3 9 9 9 2164260863 20\n");
  const CloudFile file = read_cloud_file(path);
  EXPECT_EQ(file.fields, (std::vector<std::string>{"x", "y", "z", "rgba", "label"}));
  ASSERT_EQ(file.cloud.size(), 2u);
  EXPECT_EQ(file.cloud.points[1], Eigen::Vector3f(-1, -2, -3));
  EXPECT_EQ(file.cloud.colors[0], (Color{0, 255, 0, 255}));      // 0xFF00FF00
  EXPECT_EQ(file.cloud.colors[1], (Color{255, 255, 255, 128}));  // 0x80FFFFFF
  EXPECT_EQ(file.cloud.labels, (std::vector<std::int32_t>{7, 20}));
  EXPECT_EQ(file.cloud.sensor_origin(), Eigen::Vector3d(1, 2, 3));
}

}  // namespace
}  // namespace lmk
