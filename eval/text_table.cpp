// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/text_table.h"

#include <algorithm>
#include <cstdio>

namespace lmk {

std::string TextTable::plain() const {
  std::vector<std::size_t> width(header.size(), 0);
  const auto widen = [&](const std::vector<std::string>& row) {
    for (std::size_t i = 0; i < row.size() && i < width.size(); ++i)
      width[i] = std::max(width[i], row[i].size());
  };
  widen(header);
  for (const auto& row : rows) widen(row);
  const auto line = [&](const std::vector<std::string>& row) {
    std::string out;
    for (std::size_t i = 0; i < width.size(); ++i) {
      const std::string cell = i < row.size() ? row[i] : "";
      const std::string pad(width[i] - cell.size(), ' ');
      const bool right = i < numeric.size() && numeric[i];
      out += (i ? "  " : "") + (right ? pad + cell : cell + pad);
    }
    while (!out.empty() && out.back() == ' ') out.pop_back();
    return out + "\n";
  };
  std::string out = line(header);
  std::size_t total = 0;
  for (std::size_t w : width) total += w;
  out += std::string(total + 2 * (width.empty() ? 0 : width.size() - 1), '-') + "\n";
  for (const auto& row : rows) out += line(row);
  return out;
}

std::string TextTable::markdown() const {
  const auto line = [&](const std::vector<std::string>& row) {
    std::string out = "|";
    for (std::size_t i = 0; i < header.size(); ++i)
      out += " " + (i < row.size() ? row[i] : "") + " |";
    return out + "\n";
  };
  std::string out = line(header) + "|";
  for (std::size_t i = 0; i < header.size(); ++i)
    out += (i < numeric.size() && numeric[i]) ? "---:|" : "---|";
  out += "\n";
  for (const auto& row : rows) out += line(row);
  return out;
}

std::string format_optional(const std::optional<double>& value, int decimals, double scale) {
  if (!value) return "-";
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, *value * scale);
  return text;
}

}  // namespace lmk
