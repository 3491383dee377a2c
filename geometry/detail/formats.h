// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Per-format readers and writers behind cloud_io.h. Internal: not installed.
// Readers get the whole file in memory and the path for messages; they throw lmk::Error.

#include <filesystem>
#include <optional>
#include <string>

#include "lmk/geometry/cloud_io.h"

namespace lmk::detail {

// One pass over an ASCII body from byte `offset`: the number of data rows (blank lines and lines
// starting with '#' skipped), and the first of the first `rows_to_check` rows that is not exactly
// `tokens_per_row` numbers (nan and inf included). PCL's ASCII decoders read a token such as "foo"
// as 0 or NaN without complaint; lmk refuses the file instead.
struct AsciiBodyScan {
  std::size_t rows = 0;
  std::string first_problem;  // empty when every checked row is well formed
};
AsciiBodyScan scan_ascii_body(const std::string& bytes, std::size_t offset,
                              std::size_t tokens_per_row, std::size_t rows_to_check);

// A count in a file's header as written: digits only (no sign, no exponent, at most 18 of
// them), or nothing. PCD's SIZE, COUNT, WIDTH, HEIGHT, POINTS and PLY's element counts.
inline std::optional<long long> header_count(const std::string& word) {
  if (word.empty() || word.size() > 18) return std::nullopt;
  for (char c : word) {
    if (c < '0' || c > '9') return std::nullopt;
  }
  return std::stoll(word);
}

// Each reader refuses more than `max_points` points with CloudTooLarge: from the header before
// anything is decoded (PCD, PLY), or as the rows are read (XYZ).
CloudFile read_pcd(const std::string& path, const std::string& bytes, std::size_t max_points);
CloudFile read_ply(const std::string& path, const std::string& bytes, std::size_t max_points);
CloudFile read_xyz(const std::string& path, const std::string& bytes, std::size_t max_points);

// Throws CloudTooLarge: the file declares `count` points (or "more", as its rows are read).
[[noreturn]] void too_many_points(const std::string& path, const std::string& count,
                                  std::size_t max_points);

void write_pcd(const std::filesystem::path& file, const PointCloud& cloud, Encoding encoding);
void write_ply(const std::filesystem::path& file, const PointCloud& cloud, Encoding encoding);
void write_xyz(const std::filesystem::path& file, const PointCloud& cloud);

}  // namespace lmk::detail
