// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The one exception type of lmk. Library code throws it for bad input (a file, an argument, a
// setting); algorithm outcomes such as "nothing found" go in result structs instead.
// The message names the file or field, the problem and, where there is one, the fix.

#include <stdexcept>
#include <string>

namespace lmk {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A long run (an evaluation, an ablation, the demo tasks) stopped on request, typically Ctrl-C:
/// not an error of the input. The message says what was finished and kept, and how to resume.
class Interrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Text from a file made fit for a one-line message: at most `max_chars` bytes, with control
/// characters and bytes that are not UTF-8 shown as \xNN, so that a binary file cannot garble
/// the terminal or split the line.
std::string printable(const std::string& text, std::size_t max_chars = 60);

/// Whether `text` is well-formed UTF-8 (RFC 3629: no overlong forms, no surrogates).
bool is_valid_utf8(const std::string& text);

}  // namespace lmk
