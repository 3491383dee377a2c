// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target for lmk's walk of the OpenVDB container (detail::check_vdb_layout), the check that
// stands between a file whose checksum matches and OpenVDB's own reader, which trusts every length
// it reads. fuzz_landmark rarely gets past the checksum; this target starts behind it.

#include <cstddef>
#include <cstdint>
#include <string>

#include "lmk/geometry/error.h"
#include "lmk/landmark/detail/landmark_container.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    lmk::detail::check_vdb_layout("input.lmk",
                                  std::string(reinterpret_cast<const char*>(data), size));
  } catch (const lmk::Error&) {
  }
  return 0;
}
