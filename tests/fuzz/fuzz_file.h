// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Shared by the fuzz targets: the readers under test take paths (PCL and OpenVDB open the file
// themselves), so each input is written to a file in a private temporary directory first.

#include <string>

namespace lmk::fuzz {

/// A directory of this process's own under $TMPDIR (or /tmp), removed at exit.
const std::string& scratch_dir();

/// Writes the input to scratch_dir()/name and returns the path.
std::string write_input(const std::string& name, const unsigned char* data, std::size_t size);

}  // namespace lmk::fuzz
