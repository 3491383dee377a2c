#include "geometry/detail/formats.h"

namespace lmk::detail {

std::size_t count_data_rows(const std::string& bytes, std::size_t offset) {
  std::size_t rows = 0;
  bool at_line_start = true;
  for (std::size_t i = offset; i < bytes.size(); ++i) {
    const char c = bytes[i];
    if (c == '\n') {
      at_line_start = true;
    } else if (c != ' ' && c != '\t' && c != '\r') {
      if (at_line_start && c != '#') ++rows;
      at_line_start = false;
    }
  }
  return rows;
}

}  // namespace lmk::detail
