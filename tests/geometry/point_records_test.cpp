// SPDX-License-Identifier: BSD-3-Clause
// The one reader of packed point records (geometry/point_records.h), which PCD/PLY files (through
// PCL) and ROS PointCloud2 messages both go through: its layout rules, checked on records built
// here byte by byte.
#include "lmk/geometry/point_records.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "tests/support/test_support.h"

namespace lmk {
namespace {

using Type = PointDatatype;

std::uint8_t code(Type t) { return static_cast<std::uint8_t>(t); }

// Rows of points laid out as `fields` say, `pad` spare bytes at the end of each row.
struct Layout {
  std::vector<RecordField> fields;
  std::uint32_t point_step = 0;
  std::uint32_t width = 0, height = 0, pad = 0;
  std::vector<std::uint8_t> bytes;

  std::uint8_t* at(std::uint32_t row, std::uint32_t col, const std::string& field) {
    for (const RecordField& f : fields) {
      if (f.name == field) return bytes.data() + row * row_step() + col * point_step + f.offset;
    }
    ADD_FAILURE() << "no field " << field;
    return bytes.data();
  }
  std::uint32_t row_step() const { return width * point_step + pad; }
  PointRecords records() const {
    return {fields, width, height, point_step, row_step(), bytes.data(), bytes.size()};
  }
};

template <typename T>
void put(std::uint8_t* p, T v) {
  std::memcpy(p, &v, sizeof v);
}

// x as a double, y as an int16, z as a float, a uint8 in between, an rgba, an int8 label: every
// value at its offset, rows padded.
Layout mixed_layout() {
  Layout l;
  l.fields = {{"x", 0, code(Type::kFloat64)},    {"y", 8, code(Type::kInt16)},
              {"_", 10, code(Type::kUint8)},     {"z", 12, code(Type::kFloat32)},
              {"rgba", 16, code(Type::kUint32)}, {"label", 20, code(Type::kInt8)}};
  l.point_step = 24;
  l.width = 3;
  l.height = 2;
  l.pad = 8;
  l.bytes.assign(l.row_step() * l.height, 0xAB);
  for (std::uint32_t r = 0; r < l.height; ++r) {
    for (std::uint32_t c = 0; c < l.width; ++c) {
      put<double>(l.at(r, c, "x"), 0.5 * c);
      put<std::int16_t>(l.at(r, c, "y"), static_cast<std::int16_t>(-3 * r));
      put<float>(l.at(r, c, "z"), 1.0f + c + 10.0f * r);
      put<std::uint32_t>(l.at(r, c, "rgba"), 0x80102030u + c);
      put<std::int8_t>(l.at(r, c, "label"), static_cast<std::int8_t>(-1 - c));
    }
  }
  return l;
}

TEST(PointRecords, ReadsEveryFieldAtItsOffsetWhateverItsTypeAndKeepsTheRows) {
  const Layout l = mixed_layout();
  const PointCloud cloud = decode_point_records(l.records(), "test");
  ASSERT_EQ(cloud.size(), 6u);
  EXPECT_TRUE(cloud.is_organized());
  EXPECT_EQ(cloud.width, 3u);
  EXPECT_EQ(cloud.height, 2u);
  EXPECT_FALSE(cloud.has_normals());
  for (std::uint32_t r = 0; r < 2; ++r) {
    for (std::uint32_t c = 0; c < 3; ++c) {
      const std::size_t i = r * 3 + c;
      EXPECT_EQ(cloud.points[i], Eigen::Vector3f(0.5f * c, -3.0f * r, 1.0f + c + 10.0f * r)) << i;
      // 0xAARRGGBB: alpha 0x80, then 0x10, 0x20, 0x30 + c.
      EXPECT_EQ(cloud.colors[i].a, 0x80);
      EXPECT_EQ(cloud.colors[i].r, 0x10);
      EXPECT_EQ(cloud.colors[i].g, 0x20);
      EXPECT_EQ(cloud.colors[i].b, 0x30 + c);
      EXPECT_EQ(cloud.labels[i], -1 - static_cast<int>(c));
    }
  }
}

TEST(PointRecords, AFloatRgbIsABitPatternWithoutAlpha) {
  Layout l;
  l.fields = {{"x", 0, code(Type::kFloat32)},
              {"y", 4, code(Type::kFloat32)},
              {"z", 8, code(Type::kFloat32)},
              {"rgb", 12, code(Type::kFloat32)}};
  l.point_step = 16;
  l.width = 1;
  l.height = 1;
  l.bytes.assign(16, 0);
  put<std::uint32_t>(l.at(0, 0, "rgb"), pack_point_color(Color{200, 100, 50, 7}));
  const PointCloud cloud = decode_point_records(l.records(), "test");
  ASSERT_EQ(cloud.colors.size(), 1u);
  EXPECT_EQ(cloud.colors[0].r, 200);
  EXPECT_EQ(cloud.colors[0].g, 100);
  EXPECT_EQ(cloud.colors[0].b, 50);
  EXPECT_EQ(cloud.colors[0].a, 255);  // "rgb" carries no alpha, whatever its top byte holds
  EXPECT_FALSE(cloud.is_organized());
}

TEST(PointRecords, NormalsAreReadWhenAllThreeArePresent) {
  Layout l;
  for (const char* name : {"x", "y", "z", "normal_x", "normal_y", "normal_z"}) {
    l.fields.push_back({name, l.point_step, code(Type::kFloat32)});
    l.point_step += 4;
  }
  l.width = 2;
  l.height = 1;
  l.bytes.assign(l.row_step(), 0);
  put<float>(l.at(0, 1, "normal_z"), 1.0f);
  const PointCloud cloud = decode_point_records(l.records(), "test");
  ASSERT_TRUE(cloud.has_normals());
  EXPECT_EQ(cloud.normals[1], Eigen::Vector3f(0, 0, 1));
  l.fields.pop_back();  // without normal_z there are none
  EXPECT_FALSE(decode_point_records(l.records(), "test").has_normals());
}

TEST(PointRecords, BadLayoutsAreRefusedNamingWhere) {
  const auto refused = [](Layout l, const std::string& what) {
    const std::string error = test::error_of([&] { decode_point_records(l.records(), "/cam"); });
    EXPECT_EQ(error.rfind("/cam: ", 0), 0u) << error;
    EXPECT_NE(error.find(what), std::string::npos) << error;
  };
  Layout no_z = mixed_layout();
  no_z.fields.erase(no_z.fields.begin() + 3);
  refused(no_z, "no x/y/z fields (it has: x y rgba label)");
  Layout unknown = mixed_layout();
  unknown.fields[0].datatype = 9;
  refused(unknown, "field 'x' has a type lmk does not read (datatype 9)");
  Layout beyond = mixed_layout();
  beyond.fields[3].offset = 22;  // a float at 22 of a 24-byte point
  refused(beyond, "field 'z' lies beyond the point step (24 bytes)");
  Layout truncated = mixed_layout();
  truncated.bytes.resize(truncated.bytes.size() - truncated.pad - 1);  // the last point's last byte
  refused(truncated, "bytes of points, but its rows need");
  Layout zero_step = mixed_layout();
  zero_step.point_step = 0;
  refused(zero_step, "field 'x' lies beyond the point step (0 bytes)");
  // The padding of the last row may be missing: the rows still hold every point.
  Layout unpadded_end = mixed_layout();
  unpadded_end.bytes.resize(unpadded_end.bytes.size() - unpadded_end.pad);
  EXPECT_EQ(decode_point_records(unpadded_end.records(), "test").size(), 6u);
}

TEST(PointRecords, AnEmptyFrameIsAnEmptyCloud) {
  Layout l = mixed_layout();
  l.width = 0;
  l.bytes.clear();
  EXPECT_EQ(decode_point_records(l.records(), "test").size(), 0u);
}

}  // namespace
}  // namespace lmk
