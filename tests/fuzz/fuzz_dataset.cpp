// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target for the dataset loader (load_dataset): the input is a dataset.json in a directory
// that also holds a scene "scene.pcd" and a landmark "landmark.lmk" (empty files: the loader
// checks that the files exist, not what they hold), so that inputs naming them reach the checks of
// pairs, instances and hidden fractions.

#include <cstddef>
#include <cstdint>

#include "lmk/datasets/dataset.h"
#include "lmk/geometry/error.h"
#include "tests/fuzz/fuzz_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool files_made = [] {
    lmk::fuzz::write_input("scene.pcd", nullptr, 0);
    lmk::fuzz::write_input("landmark.lmk", nullptr, 0);
    return true;
  }();
  (void)files_made;
  lmk::fuzz::write_input("dataset.json", data, size);
  try {
    lmk::load_dataset(lmk::fuzz::scratch_dir());
  } catch (const lmk::Error&) {
  }
  return 0;
}
