// SPDX-License-Identifier: BSD-3-Clause
// Depth and colour images: PNG and PGM round trips through libpng, the back-projection of the
// pinhole model, and a clear error for every kind of bad file.

#include "lmk/geometry/depth_image.h"

#include <gtest/gtest.h>

#include "tests/support/test_support.h"

namespace lmk {
namespace {

using test::error_of;
using test::ScratchDir;
using test::write_text;

DepthImage ramp(int width, int height) {
  DepthImage d;
  d.width = width;
  d.height = height;
  for (int i = 0; i < width * height; ++i) d.depth.push_back(static_cast<std::uint16_t>(i * 257));
  return d;
}

TEST(DepthImage, PngRoundTripKeepsEverySample) {
  const ScratchDir dir;
  const DepthImage d = ramp(7, 5);
  write_text(dir.file("d.png"), depth_png(d));
  const DepthImage back = read_depth_image(dir.file("d.png"));
  EXPECT_EQ(back.width, 7);
  EXPECT_EQ(back.height, 5);
  EXPECT_EQ(back.depth, d.depth);  // 16-bit, big-endian in the file, host order in memory
}

TEST(DepthImage, PgmIsReadBigEndianPastItsComments) {
  const ScratchDir dir;
  std::string pgm = "P5\n# a comment\n3 2\n65535\n";
  for (std::uint16_t v : {1, 256, 1000, 0, 65535, 7}) {
    pgm += static_cast<char>(v >> 8);
    pgm += static_cast<char>(v & 0xff);
  }
  write_text(dir.file("d.pgm"), pgm);
  const DepthImage d = read_depth_image(dir.file("d.pgm"));
  EXPECT_EQ(d.depth, (std::vector<std::uint16_t>{1, 256, 1000, 0, 65535, 7}));
}

TEST(DepthImage, ColourPngRoundTripsInEveryLayoutLibpngExpands) {
  const ScratchDir dir;
  ColourImage c;
  c.width = 2;
  c.height = 2;
  c.pixels = {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255}, {10, 20, 30, 255}};
  write_text(dir.file("c.png"), colour_png(c));
  EXPECT_EQ(read_colour_image(dir.file("c.png")).pixels, c.pixels);
  // Greyscale becomes three equal channels.
  write_text(dir.file("g.png"), greyscale_png({0, 100, 200, 255}, 2, 2));
  const ColourImage g = read_colour_image(dir.file("g.png"));
  EXPECT_EQ(g.pixels[1], (Color{100, 100, 100, 255}));
}

TEST(DepthImage, BackProjectsThroughThePinholeModel) {
  DepthImage d;
  d.width = 4;
  d.height = 3;
  d.depth.assign(12, 0);
  d.depth[1 * 4 + 3] = 2000;  // (u, v) = (3, 1), 2 m
  const PinholeIntrinsics k{500.0, 400.0, 1.5, 1.0};
  const PointCloud cloud = depth_to_cloud(d, k);
  ASSERT_EQ(cloud.width, 4u);
  ASSERT_EQ(cloud.height, 3u);
  EXPECT_EQ(cloud.count_finite(), 1u);
  const Eigen::Vector3f p = cloud.points[1 * 4 + 3];
  EXPECT_NEAR(p.x(), (3 - 1.5) * 2.0 / 500.0, 1e-6);
  EXPECT_NEAR(p.y(), 0.0, 1e-6);
  EXPECT_NEAR(p.z(), 2.0, 1e-6);
  // Projected back, the point lands on its pixel.
  EXPECT_NEAR(k.fx * p.x() / p.z() + k.cx, 3.0, 1e-4);
  // The depth unit scales; depths outside the range are no return.
  DepthToCloud tum;
  tum.metres_per_unit = 1.0 / 5000.0;
  EXPECT_NEAR(depth_to_cloud(d, k, tum).points[7].z(), 0.4, 1e-6);
  tum.min_depth = 0.5;
  EXPECT_EQ(depth_to_cloud(d, k, tum).count_finite(), 0u);
}

TEST(DepthImage, ColourMustBeRegisteredPixelForPixel) {
  const DepthImage d = ramp(4, 3);
  ColourImage c;
  c.width = 4;
  c.height = 3;
  c.pixels.assign(12, Color{1, 2, 3, 255});
  const PointCloud cloud = depth_to_cloud(d, {500, 500, 2, 1}, {}, &c);
  ASSERT_TRUE(cloud.has_colors());
  EXPECT_EQ(cloud.colors[5], (Color{1, 2, 3, 255}));
  c.width = 2;
  c.pixels.resize(6);
  EXPECT_NE(error_of([&] {
              depth_to_cloud(d, {500, 500, 2, 1}, {}, &c);
            }).find("registered"),
            std::string::npos);
}

TEST(DepthImage, BadFilesAreClearErrorsNamingTheFile) {
  const ScratchDir dir;
  const auto refused = [&](const std::string& name, const std::string& bytes,
                           const std::string& expected) {
    write_text(dir.file(name), bytes);
    const std::string why = error_of([&] { read_depth_image(dir.file(name)); });
    EXPECT_NE(why.find(dir.file(name)), std::string::npos) << why;
    EXPECT_NE(why.find(expected), std::string::npos) << name << ": " << why;
  };
  refused("text.png", "not an image at all", "not a PNG");
  const std::string png = depth_png(ramp(16, 16));
  refused("cut.png", png.substr(0, png.size() / 2), "not a readable PNG");
  std::string corrupt = png;
  corrupt[png.size() - 20] ^= 0x55;  // inside the image data: a CRC error
  refused("corrupt.png", corrupt, "not a readable PNG");
  refused("grey8.png", greyscale_png({1, 2, 3, 4}, 2, 2), "16-bit greyscale");
  refused("rgb.pgm", "P6\n2 2\n255\n", "not a binary PGM");
  refused("byte.pgm", "P5\n1 1\n255\n\x01", "16-bit samples");
  refused("short.pgm", "P5\n4 4\n65535\n\x01\x02", "ends early");
  refused("huge.pgm", "P5\n99999999 99999999\n65535\n", "more than lmk reads");
  // 64 million pixels took 3.65 GB and became a cloud lmk's reader refuses (issue #47).
  refused("8k.pgm", "P5\n8000 8000\n65535\n", "more than lmk reads");
  refused("depth.jpg", "x", ".png or .pgm");
  EXPECT_NE(error_of([&] { read_depth_image(dir.file("missing.png")); }), "");
}

TEST(Intrinsics, ReadsACameraMatrixOrFourNumbers) {
  const ScratchDir dir;
  write_text(dir.file("k.txt"), "585 0 320\n0 585 240\n0 0 1\n");
  const PinholeIntrinsics k = read_intrinsics(dir.file("k.txt"));
  EXPECT_EQ(k.fx, 585.0);
  EXPECT_EQ(k.cy, 240.0);
  write_text(dir.file("k4.txt"), "517.3 516.5 318.6 255.3");
  EXPECT_EQ(read_intrinsics(dir.file("k4.txt")).fy, 516.5);
  write_text(dir.file("bad.txt"), "585 1 320\n0 585 240\n0 0 1\n");
  EXPECT_NE(error_of([&] { read_intrinsics(dir.file("bad.txt")); }).find("camera matrix"),
            std::string::npos);
  write_text(dir.file("neg.txt"), "-5 5 1 1");
  EXPECT_NE(error_of([&] { read_intrinsics(dir.file("neg.txt")); }).find("positive"),
            std::string::npos);
  write_text(dir.file("word.txt"), "5 5 x 1");
  EXPECT_NE(error_of([&] { read_intrinsics(dir.file("word.txt")); }).find("'x'"),
            std::string::npos);
}

}  // namespace
}  // namespace lmk
