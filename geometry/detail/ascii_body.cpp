// SPDX-License-Identifier: BSD-3-Clause
// The shared scan of ASCII cloud bodies (PCD and PLY), before PCL decodes them.

#include <cstdlib>
#include <sstream>

#include "lmk/geometry/detail/formats.h"
#include "lmk/geometry/error.h"

namespace lmk::detail {

AsciiBodyScan scan_ascii_body(const std::string& bytes, std::size_t offset,
                              std::size_t tokens_per_row, std::size_t rows_to_check) {
  AsciiBodyScan scan;
  std::istringstream body(bytes.substr(offset));
  std::string line, token;
  while (std::getline(body, line)) {
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    ++scan.rows;
    if (!scan.first_problem.empty() || scan.rows > rows_to_check) continue;
    std::istringstream words(line);
    std::size_t tokens = 0;
    while (words >> token && scan.first_problem.empty()) {
      char* end = nullptr;
      std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0') {
        scan.first_problem = "data row " + std::to_string(scan.rows) + ": '" + printable(token) +
                             "' is not a number";
      }
      ++tokens;
    }
    if (scan.first_problem.empty() && tokens != tokens_per_row) {
      scan.first_problem = "data row " + std::to_string(scan.rows) + " has " +
                           std::to_string(tokens) + " values but the header's fields need " +
                           std::to_string(tokens_per_row);
    }
  }
  return scan;
}

}  // namespace lmk::detail
