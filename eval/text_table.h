// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A table of strings rendered as aligned plain text (terminals, logs) or as Markdown (reports),
// so that every table lmk prints looks the same in both.

#include <optional>
#include <string>
#include <vector>

namespace lmk {

struct TextTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  /// Column i is right-aligned in plain text (numbers) when numeric[i]; missing entries mean left.
  std::vector<bool> numeric;

  std::string plain() const;
  std::string markdown() const;
};

/// "0.950", or "-" for nothing: undefined ratios are never printed as 0 or 1.
std::string format_optional(const std::optional<double>& value, int decimals, double scale = 1.0);

}  // namespace lmk
