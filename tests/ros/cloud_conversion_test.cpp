// SPDX-License-Identifier: BSD-3-Clause
// sensor_msgs/PointCloud2 <-> lmk::PointCloud: the grid, the NaNs, colours and labels survive both
// ways, a cloud packed by PCL's own conversion reads back as PCL meant it, and malformed messages
// are refused with a reason.
#include "lmk/ros/cloud_conversion.h"

#include <gtest/gtest.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl_conversions/pcl_conversions.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "tests/support/test_support.h"

namespace lmk::ros1 {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

/// A 4 x 3 organised cloud with NaN holes, colours and labels, like a depth camera's frame.
PointCloud organised_frame() {
  PointCloud cloud;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 4; ++col) {
      const bool hole = (row + col) % 5 == 0;
      cloud.points.emplace_back(hole ? kNaN : 0.1f * col, hole ? kNaN : 0.1f * row,
                                hole ? kNaN : 1.0f + 0.01f * (row * 4 + col));
      cloud.colors.push_back(
          Color{static_cast<std::uint8_t>(20 * col), static_cast<std::uint8_t>(50 * row), 7, 255});
      cloud.labels.push_back(row * 4 + col - 3);
    }
  }
  cloud.width = 4;
  cloud.height = 3;
  return cloud;
}

/// Bit-for-bit equal points (NaN holes in the same places), same grid and attributes.
void expect_same_cloud(const PointCloud& a, const PointCloud& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(std::memcmp(a.points[i].data(), b.points[i].data(), 3 * sizeof(float)), 0) << i;
  }
  EXPECT_EQ(a.colors, b.colors);
  EXPECT_EQ(a.labels, b.labels);
}

TEST(CloudConversion, OrganisedFrameWithHolesColoursAndLabelsRoundTrips) {
  const PointCloud cloud = organised_frame();
  const sensor_msgs::PointCloud2 msg = to_ros(cloud, "head_mount_kinect_rgb_optical_frame");
  EXPECT_EQ(msg.header.frame_id, "head_mount_kinect_rgb_optical_frame");
  EXPECT_EQ(msg.width, 4u);
  EXPECT_EQ(msg.height, 3u);
  EXPECT_FALSE(msg.is_dense);
  expect_same_cloud(from_ros(msg), cloud);
}

TEST(CloudConversion, UnorganisedCloudWithoutColourRoundTrips) {
  const PointCloud cloud = test::random_cloud(500, 3);
  const sensor_msgs::PointCloud2 msg = to_ros(cloud, "base_link");
  EXPECT_EQ(msg.height, 1u);
  EXPECT_EQ(msg.fields.size(), 3u);
  EXPECT_TRUE(msg.is_dense);
  const PointCloud back = from_ros(msg);
  expect_same_cloud(back, cloud);
  EXPECT_FALSE(back.is_organized());
  EXPECT_FALSE(back.has_colors());
}

TEST(CloudConversion, ReadsWhatPclPacksColourAndHolesIncluded) {
  pcl::PointCloud<pcl::PointXYZRGB> pcl_cloud(3, 2);
  for (std::size_t i = 0; i < pcl_cloud.size(); ++i) {
    pcl::PointXYZRGB& p = pcl_cloud[i];
    p.x = 0.5f * i;
    p.y = -0.25f * i;
    p.z = 2.0f;
    p.r = static_cast<std::uint8_t>(40 * i);
    p.g = 200;
    p.b = static_cast<std::uint8_t>(255 - i);
  }
  pcl_cloud[4].x = pcl_cloud[4].y = pcl_cloud[4].z = kNaN;
  pcl_cloud.is_dense = false;
  pcl::PCLPointCloud2 packed;
  pcl::toPCLPointCloud2(pcl_cloud, packed);
  sensor_msgs::PointCloud2 msg;
  pcl_conversions::moveFromPCL(packed, msg);

  const PointCloud cloud = from_ros(msg);
  ASSERT_EQ(cloud.size(), 6u);
  EXPECT_EQ(cloud.width, 3u);
  EXPECT_EQ(cloud.height, 2u);
  ASSERT_TRUE(cloud.has_colors());
  for (std::size_t i = 0; i < 6; ++i) {
    if (i == 4) {
      EXPECT_TRUE(std::isnan(cloud.points[i].x()));
      continue;
    }
    EXPECT_EQ(cloud.points[i], Eigen::Vector3f(0.5f * i, -0.25f * i, 2.0f));
    EXPECT_EQ(cloud.colors[i], (Color{static_cast<std::uint8_t>(40 * i), 200,
                                      static_cast<std::uint8_t>(255 - i), 255}));
  }
  // And PCL reads what lmk writes.
  pcl::PCLPointCloud2 again;
  pcl_conversions::toPCL(to_ros(cloud, "f"), again);
  pcl::PointCloud<pcl::PointXYZRGB> round;
  pcl::fromPCLPointCloud2(again, round);
  ASSERT_EQ(round.size(), 6u);
  EXPECT_EQ(round[2].r, 80);
  EXPECT_EQ(round[2].g, 200);
  EXPECT_EQ(round[2].b, 253);
  EXPECT_EQ(round.height, 2u);
}

TEST(CloudConversion, ReadsDoubleCoordinatesPaddingAndPaddedRows) {
  // Two points per row, each x, y, z as FLOAT64 after 4 bytes of padding; rows padded by 8 bytes.
  sensor_msgs::PointCloud2 msg;
  msg.width = 2;
  msg.height = 2;
  msg.point_step = 4 + 3 * 8;
  msg.row_step = msg.width * msg.point_step + 8;
  for (const char* name : {"x", "y", "z"}) {
    sensor_msgs::PointField f;
    f.name = name;
    f.offset = static_cast<std::uint32_t>(4 + 8 * msg.fields.size());
    f.datatype = sensor_msgs::PointField::FLOAT64;
    f.count = 1;
    msg.fields.push_back(f);
  }
  msg.data.assign(msg.row_step * msg.height, 0xEE);
  for (int row = 0; row < 2; ++row) {
    for (int col = 0; col < 2; ++col) {
      for (int axis = 0; axis < 3; ++axis) {
        const double v = 100.0 * row + 10.0 * col + axis;
        std::memcpy(&msg.data[row * msg.row_step + col * msg.point_step + 4 + 8 * axis], &v, 8);
      }
    }
  }
  const PointCloud cloud = from_ros(msg);
  ASSERT_EQ(cloud.size(), 4u);
  EXPECT_EQ(cloud.points[3], Eigen::Vector3f(110, 111, 112));
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(10, 11, 12));
  EXPECT_TRUE(cloud.is_organized());
}

TEST(CloudConversion, MalformedMessagesAreRefusedWithTheReason) {
  const sensor_msgs::PointCloud2 good = to_ros(test::random_cloud(10, 1), "f");

  sensor_msgs::PointCloud2 no_z = good;
  no_z.fields.pop_back();
  EXPECT_NE(test::error_of([&] {
              from_ros(no_z, "/points");
            }).find("/points: no x/y/z fields (it has: x y)"),
            std::string::npos);

  sensor_msgs::PointCloud2 big_endian = good;
  big_endian.is_bigendian = true;
  EXPECT_NE(test::error_of([&] { from_ros(big_endian); }).find("big-endian"), std::string::npos);

  sensor_msgs::PointCloud2 truncated = good;
  truncated.data.resize(truncated.data.size() - 1);
  EXPECT_NE(test::error_of([&] { from_ros(truncated); }).find("bytes"), std::string::npos);

  sensor_msgs::PointCloud2 outside = good;
  outside.fields[2].offset = outside.point_step - 2;
  EXPECT_NE(test::error_of([&] { from_ros(outside); }).find("beyond the point step"),
            std::string::npos);

  // Datatype 0 is none of PointField's: refused, never read as some size.
  sensor_msgs::PointCloud2 unknown_type = good;
  unknown_type.fields[0].datatype = 0;
  EXPECT_NE(test::error_of([&] { from_ros(unknown_type); }).find("a type lmk does not read"),
            std::string::npos);
}

}  // namespace
}  // namespace lmk::ros1
