// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A minimal PNG writer for the report's failure pictures (8-bit greyscale, deflate "stored"
// blocks: no compression library needed, and a picture of 160 x 120 pixels is 19 KB). Internal.

#include <cstdint>
#include <string>
#include <vector>

namespace lmk::detail {

/// The PNG file of a width x height greyscale image (row-major, one byte per pixel).
std::string greyscale_png(const std::vector<std::uint8_t>& pixels, int width, int height);

/// `bytes` in base64 (RFC 4648), for data: URIs.
std::string base64(const std::string& bytes);

}  // namespace lmk::detail
