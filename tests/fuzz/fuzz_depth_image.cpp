// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target for the depth-image readers (read_depth_image, through libpng for PNG): built once
// per format, with LMK_FUZZ_EXTENSION ".png" or ".pgm". An input must either read as a consistent
// image, which back-projects to a consistent organised cloud, or be refused with lmk::Error; any
// other exception, crash, sanitizer report, or allocation over libFuzzer's limit is a finding.

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "lmk/geometry/depth_image.h"
#include "lmk/geometry/error.h"
#include "tests/fuzz/fuzz_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = lmk::fuzz::write_input("input" LMK_FUZZ_EXTENSION, data, size);
  try {
    const lmk::DepthImage image = lmk::read_depth_image(path);
    if (image.width <= 0 || image.height <= 0) std::abort();
    const std::size_t n = std::size_t(image.width) * std::size_t(image.height);
    if (image.depth.size() != n || n > lmk::kMaxImagePixels) std::abort();
    const lmk::PointCloud cloud = lmk::depth_to_cloud(image, lmk::PinholeIntrinsics{});
    if (cloud.size() != n || std::size_t{cloud.width} * cloud.height != n) std::abort();
  } catch (const lmk::Error&) {
    // a refusal, with its one-line message
  }
  return 0;
}
