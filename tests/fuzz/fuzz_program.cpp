// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target for the PbD program loader (load_program): JSON of any shape must either give a
// program that passes validation or be refused with lmk::Error naming the file and field.

#include <cstddef>
#include <cstdint>

#include "lmk/geometry/error.h"
#include "lmk/pbd/program.h"
#include "tests/fuzz/fuzz_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = lmk::fuzz::write_input("program.json", data, size);
  try {
    const lmk::Program program = lmk::load_program(path);
    lmk::validate_program(program);
  } catch (const lmk::Error&) {
  }
  return 0;
}
