// SPDX-License-Identifier: BSD-3-Clause
// The failure pictures' PNG writer and base64: the format's fixed parts, checked by hand.

#include "lmk/eval/detail/png.h"

#include <gtest/gtest.h>

#include "lmk/geometry/error.h"

namespace lmk::detail {
namespace {

TEST(Png, AGreyscaleImageHasTheFormatsFixedParts) {
  const std::vector<std::uint8_t> pixels = {0, 64, 128, 255, 1, 2};
  const std::string png = greyscale_png(pixels, 3, 2);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // IHDR: 13 bytes, width 3, height 2, 8-bit greyscale.
  EXPECT_EQ(png.substr(8, 8), std::string("\0\0\0\x0dIHDR", 8));
  EXPECT_EQ(png.substr(16, 8), std::string("\0\0\0\x03\0\0\0\x02", 8));
  EXPECT_EQ(png.substr(24, 2), std::string("\x08\x00", 2));
  // The last chunk is IEND with its well-known CRC.
  EXPECT_EQ(png.substr(png.size() - 12), std::string("\0\0\0\0IEND\xae\x42\x60\x82", 12));
  // The pixels are stored as they are, each row after its filter byte.
  EXPECT_NE(png.find(std::string("\0\0\x40\x80\0\xff\x01\x02", 8)), std::string::npos);
  EXPECT_THROW(greyscale_png(pixels, 4, 2), Error);
}

TEST(Base64, EncodesAsRfc4648) {
  EXPECT_EQ(base64(""), "");
  EXPECT_EQ(base64("M"), "TQ==");
  EXPECT_EQ(base64("Ma"), "TWE=");
  EXPECT_EQ(base64("Man"), "TWFu");
  EXPECT_EQ(base64("any carnal pleasure."), "YW55IGNhcm5hbCBwbGVhc3VyZS4=");
}

}  // namespace
}  // namespace lmk::detail
