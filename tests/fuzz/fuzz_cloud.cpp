// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target for the point-cloud readers (read_cloud_file): built once per format, with
// LMK_FUZZ_EXTENSION ".pcd", ".ply" or ".xyz". An input must either read as a consistent cloud or
// be refused with lmk::Error; any other exception, crash, sanitizer report, or allocation over
// libFuzzer's limit is a finding.

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "tests/fuzz/fuzz_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = lmk::fuzz::write_input("input" LMK_FUZZ_EXTENSION, data, size);
  try {
    const lmk::CloudFile file = lmk::read_cloud_file(path);
    const lmk::PointCloud& cloud = file.cloud;
    // What every reader promises: an organised cloud has width x height points, attributes are
    // per point, and the sensor pose is a finite rigid transform.
    const std::size_t n = cloud.size();
    if (std::size_t{cloud.width} * cloud.height != n) std::abort();
    if (!cloud.normals.empty() && cloud.normals.size() != n) std::abort();
    if (!cloud.colors.empty() && cloud.colors.size() != n) std::abort();
    if (!cloud.labels.empty() && cloud.labels.size() != n) std::abort();
    if (!cloud.T_cloud_sensor.matrix().allFinite()) std::abort();
  } catch (const lmk::Error&) {
    // a refusal, with its one-line message: the expected outcome for most inputs
  }
  return 0;
}
