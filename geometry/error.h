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
/// characters (C0, DEL and C1), bidirectional controls (U+202E and its kin) and bytes that are not
/// UTF-8 shown as \xNN, so that a binary file cannot garble the terminal, split the line or turn
/// it around.
std::string printable(const std::string& text, std::size_t max_chars = 60);

/// How much of what a client or a file sent is echoed back in a message or a log line, bytes.
inline constexpr std::size_t kEchoedBytes = 200;
/// How much of a file name the tools print, bytes: a path, whole, and never a screenful.
inline constexpr std::size_t kMaxPrintedPath = 4096;

/// Whether `text` is well-formed UTF-8 without control characters (C0, DEL, C1, bidirectional): a
/// name or a path that can be printed as it is.
bool is_printable_text(const std::string& text);

/// Whether `text` is well-formed UTF-8 (RFC 3629: no overlong forms, no surrogates).
bool is_valid_utf8(const std::string& text);

}  // namespace lmk
