// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/cloud_io.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/detail/formats.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/input_file.h"
#include "lmk/geometry/point_records.h"

namespace lmk {

namespace fs = std::filesystem;

namespace {

std::string read_cloud_bytes(const std::string& path) {
  std::string bytes = read_input_file(path, kCloudInput);
  if (bytes.empty()) throw Error(path + ": file is empty");
  return bytes;
}

}  // namespace

const char* to_string(CloudFormat format) {
  switch (format) {
    case CloudFormat::kPcd:
      return "pcd";
    case CloudFormat::kPly:
      return "ply";
    case CloudFormat::kXyz:
      return "xyz";
  }
  return "?";
}

const char* to_string(Encoding encoding) {
  switch (encoding) {
    case Encoding::kAscii:
      return "ascii";
    case Encoding::kBinary:
      return "binary";
    case Encoding::kBinaryCompressed:
      return "binary_compressed";
  }
  return "?";
}

CloudFormat format_from_path(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".pcd") return CloudFormat::kPcd;
  if (ext == ".ply") return CloudFormat::kPly;
  if (ext == ".xyz") return CloudFormat::kXyz;
  throw Error(path + ": unknown extension '" + ext + "' (supported: .pcd, .ply, .xyz)");
}

namespace detail {

void too_many_points(const std::string& path, const std::string& count, std::size_t max_points) {
  const std::string limit = std::to_string(max_points);
  throw CloudTooLarge(count == "more"
                          ? path + ": holds more than " + limit + " points, the most allowed"
                          : path + ": declares " + count + " points, over the limit of " + limit);
}

}  // namespace detail

namespace {

// The bytes per point a PCD reader decodes, from the FIELDS, SIZE and COUNT lines; 0 when they
// disagree (the reader refuses such a file before decoding it).
std::size_t pcd_decoded_point_bytes(const std::vector<std::string>& names,
                                    const std::vector<long long>& sizes,
                                    const std::vector<long long>& counts, bool compressed) {
  if (sizes.size() != names.size() || (!counts.empty() && counts.size() != names.size())) return 0;
  std::size_t bytes = 0;
  for (std::size_t f = 0; f < names.size(); ++f) {
    const std::size_t count = counts.empty() ? 1 : static_cast<std::size_t>(counts[f]);
    if (!compressed) {
      bytes += static_cast<std::size_t>(sizes[f]) * std::min(count, kMaxPcdPointBytes);
    } else if (is_read_field(names[f])) {
      bytes += static_cast<std::size_t>(sizes[f]);  // one value each
    }
  }
  return bytes;
}

}  // namespace

std::optional<DeclaredCloud> declared_cloud(const std::string& path) {
  const CloudFormat format = format_from_path(path);
  if (format == CloudFormat::kXyz) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  std::string head(64 * 1024, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  std::istringstream lines(head);
  long long width = -1, height = -1, points = -1;
  std::vector<std::string> names;
  std::vector<long long> sizes, counts;
  bool compressed = false;
  const auto count = [](const std::string& w) { return detail::header_count(w).value_or(-1); };
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string key, a, b;
    words >> key >> a >> b;
    if (format == CloudFormat::kPly) {
      if (key == "element" && a == "vertex" && count(b) >= 0) {
        return DeclaredCloud{static_cast<std::size_t>(count(b)), 0};
      }
      if (key == "end_header") break;
      continue;
    }
    std::vector<std::string> values;
    for (const std::string& w : {a, b}) {
      if (!w.empty()) values.push_back(w);
    }
    for (std::string w; words >> w;) values.push_back(w);
    if (key == "POINTS") points = values.empty() ? -1 : count(values[0]);
    if (key == "WIDTH") width = values.empty() ? -1 : count(values[0]);
    if (key == "HEIGHT") height = values.empty() ? -1 : count(values[0]);
    if (key == "FIELDS" || key == "COLUMNS") names = values;
    if (key == "SIZE" || key == "COUNT") {
      std::vector<long long>& numbers = key == "SIZE" ? sizes : counts;
      for (const std::string& v : values) numbers.push_back(std::max(count(v), 0LL));
    }
    if (key == "DATA") {
      compressed = a == "binary_compressed";
      break;
    }
  }
  if (format == CloudFormat::kPly) return std::nullopt;
  if (points < 0 && width >= 0 && height >= 0) points = width * height;
  if (points < 0) return std::nullopt;
  return DeclaredCloud{static_cast<std::size_t>(points),
                       pcd_decoded_point_bytes(names, sizes, counts, compressed)};
}

std::size_t cloud_read_price(std::size_t file_bytes, std::size_t points,
                             std::size_t decoded_point_bytes) {
  constexpr std::size_t kParseBytesPerPoint = 80;
  return 2 * file_bytes + points * (kParseBytesPerPoint + decoded_point_bytes);
}

std::size_t cloud_read_price(const std::string& path) {
  std::error_code error;
  const std::size_t size = fs::file_size(path, error);
  if (error) return 0;  // the reader names what is wrong
  const std::optional<DeclaredCloud> declared = declared_cloud(path);
  return declared ? cloud_read_price(size, declared->points, declared->decoded_point_bytes)
                  : cloud_read_price(size, size / kLeastXyzPointBytes, 0);
}

CloudFile read_cloud_file(const std::string& path, std::size_t max_points) {
  check_input_file(path, kCloudInput);
  const CloudFormat format = format_from_path(path);
  const std::string bytes = read_cloud_bytes(path);
  CloudFile file;
  try {
    switch (format) {
      case CloudFormat::kPcd:
        file = detail::read_pcd(path, bytes, max_points);
        break;
      case CloudFormat::kPly:
        file = detail::read_ply(path, bytes, max_points);
        break;
      case CloudFormat::kXyz:
        file = detail::read_xyz(path, bytes, max_points);
        break;
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    // PCL's parsers throw on some malformed headers (std::out_of_range from a DATA line without
    // its kind, found by fuzzing): a bad file, not an internal error.
    throw Error(path + ": not a valid " + to_string(format) + " file (" + printable(e.what()) +
                ")");
  }
  file.format = format;
  file.cloud.validate(path);
  if (file.cloud.count_finite() == 0) {
    throw Error(path + ": holds " + std::to_string(file.cloud.size()) +
                " points but none with finite x, y and z");
  }
  return file;
}

PointCloud read_cloud(const std::string& path, std::size_t max_points) {
  return read_cloud_file(path, max_points).cloud;
}

void write_cloud(const std::string& path, const PointCloud& cloud, const WriteOptions& options) {
  const CloudFormat format = format_from_path(path);
  cloud.validate("write " + path);
  write_file_atomically(path, [&](const fs::path& tmp) {
    switch (format) {
      case CloudFormat::kPcd:
        detail::write_pcd(tmp, cloud, options.encoding);
        break;
      case CloudFormat::kPly:
        detail::write_ply(tmp, cloud, options.encoding);
        break;
      case CloudFormat::kXyz:
        detail::write_xyz(tmp, cloud);
        break;
    }
  });
}

}  // namespace lmk
