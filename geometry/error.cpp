// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/error.h"

#include <cstdio>

namespace lmk {

namespace {

// The length of the valid UTF-8 sequence starting at text[i] (2 to 4 bytes), or 0.
std::size_t utf8_sequence(const std::string& text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  const std::size_t length = lead >= 0xf0 && lead <= 0xf4   ? 4
                             : lead >= 0xe0                 ? 3
                             : lead >= 0xc2 && lead <= 0xdf ? 2
                                                            : 0;
  if (length == 0 || i + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xc0) != 0x80) return 0;
  }
  // RFC 3629's table: no overlong forms, no surrogates, nothing beyond U+10FFFF.
  const unsigned char second = byte(i + 1);
  if ((lead == 0xe0 && second < 0xa0) || (lead == 0xed && second > 0x9f) ||
      (lead == 0xf0 && second < 0x90) || (lead == 0xf4 && second > 0x8f)) {
    return 0;
  }
  return length;
}

// Whether the n-byte UTF-8 sequence at text[i] is a bidirectional formatting character: U+061C,
// U+200E and U+200F (marks), U+202A to U+202E (embeddings and overrides), U+2066 to U+2069
// (isolates). U+202E turns the rest of a line around: a file name could show another name, a log
// line could hide what follows it (issue #61).
bool is_bidi_control(const std::string& text, std::size_t i, std::size_t n) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[i + k]); };
  if (n == 2) return byte(0) == 0xd8 && byte(1) == 0x9c;
  if (n != 3 || byte(0) != 0xe2) return false;
  if (byte(1) == 0x80)
    return byte(2) == 0x8e || byte(2) == 0x8f || (byte(2) >= 0xaa && byte(2) <= 0xae);
  return byte(1) == 0x81 && byte(2) >= 0xa6 && byte(2) <= 0xa9;
}

// The length of the printable character at text[i]: 1 for printable ASCII, 2 to 4 for a UTF-8
// sequence that is no C1 control (U+0080 to U+009F: a terminal may read U+009B as the start of an
// escape sequence, as it reads ESC [) and no bidirectional control, 0 for anything else.
std::size_t printable_character(const std::string& text, std::size_t i) {
  const auto c = static_cast<unsigned char>(text[i]);
  if (c < 0x80) return c >= 0x20 && c < 0x7f ? 1 : 0;
  const std::size_t n = utf8_sequence(text, i);
  if (n == 2 && c == 0xc2 && static_cast<unsigned char>(text[i + 1]) < 0xa0) return 0;
  if (is_bidi_control(text, i, n)) return 0;
  return n;
}

}  // namespace

bool is_valid_utf8(const std::string& text) {
  for (std::size_t i = 0; i < text.size();) {
    if (static_cast<unsigned char>(text[i]) < 0x80) {
      ++i;
    } else if (const std::size_t n = utf8_sequence(text, i); n > 0) {
      i += n;
    } else {
      return false;
    }
  }
  return true;
}

std::string printable(const std::string& text, std::size_t max_chars) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size() && out.size() < max_chars) {
    if (const std::size_t n = printable_character(text, i); n > 0) {
      out.append(text, i, n);
      i += n;
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\x%02x", static_cast<unsigned char>(text[i]));
      out += escaped;
      ++i;
    }
  }
  return i < text.size() ? out + "..." : out;
}

bool is_printable_text(const std::string& text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = printable_character(text, i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

}  // namespace lmk
