// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target for the landmark reader (load_landmark), on files as a user would hand them over:
// the lmk trailer's checksum must catch damage before OpenVDB parses anything, so an input either
// loads as a valid landmark or is refused with lmk::Error.

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "lmk/geometry/error.h"
#include "lmk/landmark/landmark_file.h"
#include "tests/fuzz/fuzz_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = lmk::fuzz::write_input("input.lmk", data, size);
  try {
    const lmk::Landmark landmark = lmk::load_landmark(path);
    landmark.validate("fuzz");  // a loaded landmark is whole: throws lmk::Error otherwise
  } catch (const lmk::Error&) {
  }
  return 0;
}
