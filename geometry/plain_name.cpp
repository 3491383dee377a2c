// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/plain_name.h"

#include <algorithm>
#include <cctype>

namespace lmk {

bool is_plain_name(const std::string& name, std::size_t max_size) {
  if (name.empty() || name.size() > max_size || name.front() == '.' || name.front() == '-') {
    return false;
  }
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
  });
}

}  // namespace lmk
