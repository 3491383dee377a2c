// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The names lmk turns into file names inside a directory it was given: landmarks, programs,
// uploaded scenes. Plain names cannot leave the directory, hide (".x"), or read as an option to
// the shell tools a user later hands the file to ("-rf.lmk", issue #34, finding 5).
#include <cstddef>
#include <string>

namespace lmk {

/// 1 to max_size letters, digits, '-', '_' or '.', not starting with '.' or '-'.
bool is_plain_name(const std::string& name, std::size_t max_size);

}  // namespace lmk
