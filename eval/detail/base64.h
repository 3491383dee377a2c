// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Base64 for the report's data: URIs (its failure pictures are PNG files, geometry/depth_image.h).
// Internal.

#include <cstdint>
#include <string>
#include <vector>

namespace lmk::detail {

/// `bytes` in base64 (RFC 4648), for data: URIs.
std::string base64(const std::string& bytes);

}  // namespace lmk::detail
