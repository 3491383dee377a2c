// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target for the landmark reader (load_landmark), on files as a forger would hand them over
// (issue #61, finding 2): an input without a valid trailer is resealed with one, so that every
// input reaches the parsers behind the checksum. A format-5 input either loads as a valid
// landmark or is refused with lmk::Error. An OpenVDB file (formats 1 to 4) goes through what the
// caller checks before a child process decodes its grids: OpenVDB's own decoding aborts on forged
// grids, which is why it runs in a child (ChildProcess tests), and fuzzing it would only find
// those aborts again, reported by the child's sanitizer as if they were this process's.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "lmk/geometry/error.h"
#include "lmk/landmark/detail/landmark_container.h"
#include "lmk/landmark/detail/vdb_landmark_file.h"
#include "lmk/landmark/landmark_file.h"
#include "tests/fuzz/fuzz_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    lmk::detail::check_landmark_trailer("input.lmk", bytes);
  } catch (const lmk::Error&) {
    bytes += lmk::detail::landmark_trailer(bytes);  // resealed, as a forger would
  }
  if (lmk::detail::has_vdb_magic(bytes)) {
    try {
      lmk::detail::check_vdb_layout(
          "input.lmk", bytes.substr(0, bytes.size() - lmk::detail::kLandmarkTrailerSize));
    } catch (const lmk::Error&) {
    }
    return 0;
  }
  const std::string path = lmk::fuzz::write_input(
      "input.lmk", reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  try {
    const lmk::Landmark landmark = lmk::load_landmark(path);
    landmark.validate("fuzz");  // a loaded landmark is whole: throws lmk::Error otherwise
  } catch (const lmk::Error&) {
  }
  return 0;
}
