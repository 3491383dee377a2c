// SPDX-License-Identifier: BSD-3-Clause
// PCD through PCL's reader and writer. PCL parses the header and decodes the body; before it
// touches the body, lmk checks that the data really holds the points the header declares, because
// PCL's binary decoders trust the header and would read past the end of a truncated file.

#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <optional>
#include <sstream>
#include <vector>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/detail/formats.h"
#include "lmk/geometry/detail/pcd_compressed.h"
#include "lmk/geometry/detail/pcl_conversion.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/point_records.h"
#include "lmk/geometry/settings_schema.h"

namespace lmk::detail {
namespace {

// Byte offset just past the "DATA ..." header line, or npos when there is none.
std::size_t body_offset(const std::string& bytes) {
  std::size_t line = 0;
  while (line < bytes.size()) {
    const std::size_t end = bytes.find('\n', line);
    if (bytes.compare(line, 5, "DATA ") == 0)
      return end == std::string::npos ? bytes.size() : end + 1;
    if (end == std::string::npos) break;
    line = end + 1;
  }
  return std::string::npos;
}

// What the header declares, as written. Each SIZE, COUNT, WIDTH, HEIGHT and POINTS value is
// checked as it is read: PCL trusts SIZE and COUNT (a negative one crashed its body readers) and
// allocates POINTS x point size while parsing the header (a 187-byte file declaring 2e9 points was
// killed at 20 GB). Sizes must be 1, 2, 4 or 8, counts positive, point counts within
// kMaxCloudPoints; -1 for a value the header does not give.
struct Declarations {
  std::size_t fields = 0;
  std::vector<std::string> names;
  std::vector<long long> sizes, counts;
  std::vector<std::string> types;
  long long width = -1, height = -1, points = -1;
  std::vector<double> viewpoint;  // tx ty tz qw qx qy qz, when given
  std::string data;
};

// VIEWPOINT is the sensor pose: tx ty tz qw qx qy qz. PCL reads it with operator>>, which leaves
// the pose uninitialised at "nan", so that every run of `find` saw another sensor origin.
void check_viewpoint(const std::string& path, const std::string& line,
                     const std::vector<std::string>& values) {
  bool good = values.size() == 7;
  for (std::size_t i = 0; good && i < values.size(); ++i) {
    good = read_finite_number(values[i]).has_value();
  }
  if (!good) {
    throw Error(path + ": header '" + printable(line) +
                "' is not seven finite numbers (VIEWPOINT tx ty tz qw qx qy qz)");
  }
}

// PCL's header parser splits lines at spaces, tabs and carriage returns, and recognises a keyword
// by its first letters: "SIZEF 1 1 1" is a SIZE line to PCL, and a line beginning with a space is
// nothing. lmk reads a header only if PCL cannot read it otherwise: every line begins with a
// keyword spelt exactly, or with '#', each keyword comes once, and no other control character
// appears (a fuzzed "SIZEF" line after SIZE had PCL lay out 1-byte floats that lmk then read as 4).
void check_header_line(const std::string& path, const std::string& line, const std::string& key,
                       std::vector<std::string>& seen) {
  static const char* const kKeywords[] = {"VERSION",   "FIELDS", "COLUMNS", "SIZE",
                                          "TYPE",      "COUNT",  "WIDTH",   "HEIGHT",
                                          "VIEWPOINT", "POINTS", "DATA"};
  for (const char c : line) {
    if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r') {
      throw Error(path + ": header line '" + printable(line) + "' holds a control character");
    }
  }
  if (key[0] == '#') return;
  if (line.compare(0, key.size(), key) != 0) {
    throw Error(path + ": header line '" + printable(line) + "' does not begin with its keyword");
  }
  if (std::find(std::begin(kKeywords), std::end(kKeywords), key) == std::end(kKeywords)) {
    throw Error(path + ": unknown header line '" + printable(line) + "'");
  }
  if (std::find(seen.begin(), seen.end(), key) != seen.end()) {
    throw Error(path + ": header " + key + " is given twice");
  }
  seen.push_back(key);
}

Declarations read_declarations(const std::string& path, const std::string& header_text) {
  Declarations d;
  std::istringstream header(header_text);
  std::string line, key, word;
  std::vector<std::string> seen;
  while (std::getline(header, line)) {
    std::istringstream words(line);
    if (!(words >> key)) continue;
    check_header_line(path, line, key, seen);
    if (key[0] == '#') continue;
    std::vector<std::string> values;
    while (words >> word) values.push_back(word);
    if (key == "FIELDS" || key == "COLUMNS") {
      d.fields = values.size();
      d.names = values;
    }
    if (key == "TYPE") d.types = values;
    if (key == "DATA") {
      d.data = values.empty() ? "" : values[0];
      if (d.data != "ascii" && d.data != "binary" && d.data != "binary_compressed") {
        throw Error(path + ": header '" + printable(line) +
                    "' is not DATA ascii, binary or binary_compressed");
      }
    }
    if (key == "VIEWPOINT") {
      check_viewpoint(path, line, values);
      for (const std::string& v : values) d.viewpoint.push_back(*read_finite_number(v));
    }
    if (key != "SIZE" && key != "COUNT" && key != "WIDTH" && key != "HEIGHT" && key != "POINTS") {
      continue;
    }
    for (const std::string& v : values) {
      const std::optional<long long> n = header_count(v);
      if (!n) throw Error(path + ": header " + key + " '" + printable(v) + "' is not a count");
      if (key == "SIZE" && *n != 1 && *n != 2 && *n != 4 && *n != 8) {
        throw Error(path + ": header SIZE " + v + " is not 1, 2, 4 or 8 bytes");
      }
      if (key == "COUNT" && *n < 1) throw Error(path + ": header COUNT " + v + " is not positive");
      if ((key == "POINTS" || key == "WIDTH" || key == "HEIGHT") &&
          *n > static_cast<long long>(kMaxCloudPoints)) {
        throw Error(path + ": header " + key + " " + v + " is over lmk's limit of " +
                    std::to_string(kMaxCloudPoints) + " points");
      }
      if (key == "SIZE") d.sizes.push_back(*n);
      if (key == "COUNT") d.counts.push_back(*n);
      if (key == "WIDTH") d.width = *n;
      if (key == "HEIGHT") d.height = *n;
      if (key == "POINTS") d.points = *n;
    }
  }
  return d;
}

// The layout the declarations give must be whole, and the body must hold the bytes its points
// need, before PCL allocates them.
void check_declared_body(const std::string& path, Declarations d, std::size_t available) {
  if (d.counts.empty()) d.counts.assign(d.sizes.size(), 1);  // COUNT is optional
  if (d.sizes.size() != d.fields || d.counts.size() != d.fields) {
    throw Error(path + ": header lists " + std::to_string(d.fields) + " fields but " +
                std::to_string(d.sizes.size()) + " sizes and " + std::to_string(d.counts.size()) +
                " counts");
  }
  // PCL gives a field of another type or size no layout: lmk would read it with the wrong width.
  for (std::size_t f = 0; f < d.types.size() && f < d.sizes.size(); ++f) {
    const std::string& t = d.types[f];
    if (t != "F" && t != "U" && t != "I") {
      throw Error(path + ": header TYPE '" + printable(t) + "' is not F, U or I");
    }
    if (t == "F" && d.sizes[f] != 4 && d.sizes[f] != 8) {
      throw Error(path + ": header TYPE F with SIZE " + std::to_string(d.sizes[f]) +
                  ": a float is 4 or 8 bytes");
    }
  }
  std::size_t point_bytes = 0;
  for (std::size_t f = 0; f < d.fields; ++f) {
    point_bytes += static_cast<std::size_t>(d.sizes[f]) *
                   static_cast<std::size_t>(std::min<long long>(d.counts[f], kMaxPcdPointBytes));
    if (point_bytes > kMaxPcdPointBytes) {
      throw Error(path + ": header declares over " + std::to_string(kMaxPcdPointBytes) +
                  " bytes per point");
    }
  }
  if (d.points < 0) return;  // PCL refuses a header without POINTS (or WIDTH x HEIGHT)
  const std::size_t declared = static_cast<std::size_t>(d.points);
  // What the body must hold at least: binary, every byte; ASCII, a character per point; LZF
  // expands at most about 90-fold, so the compressed block bounds the points too.
  std::size_t most = available;
  if (d.data == "binary") most = point_bytes == 0 ? declared : available / point_bytes;
  if (d.data == "binary_compressed" && point_bytes > 0) most = 100 * available / point_bytes;
  if (declared > most) {
    throw Error(path + ": truncated: header declares " + std::to_string(declared) +
                " points but the data holds at most " + std::to_string(most));
  }
}

[[noreturn]] void count_mismatch(const std::string& path, std::size_t declared, std::size_t held) {
  throw Error(path + (held < declared ? ": truncated: header" : ": header") + " declares " +
              std::to_string(declared) + " points but the data holds " + std::to_string(held));
}

}  // namespace

namespace {

// What a PCD file's header declares, checked against the body's size and `max_points`, and where
// the body starts.
struct CheckedHeader {
  Declarations says;
  std::size_t offset = 0;
};

CheckedHeader check_pcd_header(const std::string& path, const std::string& bytes,
                               std::size_t max_points) {
  CheckedHeader h;
  h.offset = body_offset(bytes);
  if (h.offset == std::string::npos) {
    throw Error(path + ": not a valid PCD file (its header has no DATA line)");
  }
  h.says = read_declarations(path, bytes.substr(0, h.offset));
  const Declarations& d = h.says;
  const long long points = d.points >= 0                   ? d.points
                           : d.width >= 0 && d.height >= 0 ? d.width * d.height
                                                           : -1;
  if (points > static_cast<long long>(max_points)) {
    too_many_points(path, std::to_string(points), max_points);
  }
  check_declared_body(path, d, bytes.size() - h.offset);
  return h;
}

[[noreturn]] void inconsistent_points(const std::string& path, const Declarations& d) {
  throw Error(path + ": inconsistent header: WIDTH x HEIGHT = " + std::to_string(d.width) + " x " +
              std::to_string(d.height) + " but POINTS " + std::to_string(d.points));
}

// What PCL's header parser makes of the header: the fields (in `blob`, its data allocated for the
// declared points, which check_pcd_header has bounded by the body's size), the sensor pose, the
// format's version and encoding.
struct PcdHeader {
  pcl::PCLPointCloud2 blob;
  Eigen::Vector4f origin = Eigen::Vector4f::Zero();
  Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();
  int version = 0, data_type = 0;
  std::size_t offset = 0;
};

PcdHeader read_pcd_header(pcl::PCDReader& reader, const std::string& path, const std::string& bytes,
                          const CheckedHeader& checked) {
  PcdHeader h;
  h.offset = checked.offset;
  unsigned int pcl_data_idx = 0;  // unused: lmk finds the body itself, for its size checks
  // PCL's header parser reads on after the DATA line while lines look like header lines: a fuzzed
  // ASCII body beginning "COLUMNS..." and "POINTS 8277990003" made it allocate a terabyte. It is
  // given the header alone.
  std::istringstream header(bytes.substr(0, h.offset));
  if (reader.readHeader(header, h.blob, h.origin, h.orientation, h.version, h.data_type,
                        pcl_data_idx) < 0) {
    const Declarations& c = checked.says;
    if (c.width >= 0 && c.height >= 0 && c.points >= 0 && c.width * c.height != c.points) {
      inconsistent_points(path, c);
    }
    throw Error(path + ": not a valid PCD file (its header could not be parsed)");
  }
  return h;
}

// An ASCII or binary body decoded into h.blob by PCL, its size checked first; the encoding it had.
Encoding read_pcd_body(pcl::PCDReader& reader, const std::string& path, const std::string& bytes,
                       PcdHeader& h) {
  const std::size_t declared = static_cast<std::size_t>(h.blob.width) * h.blob.height;
  const std::size_t step = h.blob.point_step;
  const std::size_t available = bytes.size() - std::min(h.offset, bytes.size());
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  int status = 0;
  Encoding encoding = Encoding::kAscii;
  if (h.data_type == 0) {
    std::size_t tokens_per_row = 0;
    for (const pcl::PCLPointField& f : h.blob.fields) tokens_per_row += f.count;
    // A count mismatch is reported first: a file cut mid-row is truncated, not malformed.
    const AsciiBodyScan scan = scan_ascii_body(bytes, h.offset, tokens_per_row, declared);
    if (scan.rows != declared) count_mismatch(path, declared, scan.rows);
    if (!scan.first_problem.empty()) throw Error(path + ": " + scan.first_problem);
    std::istringstream body(bytes);
    body.seekg(static_cast<std::streamoff>(h.offset));
    status = reader.readBodyASCII(body, h.blob, h.version);
  } else {
    encoding = Encoding::kBinary;
    if (step == 0) throw Error(path + ": header declares fields of zero size");
    // Only a shortfall is an error: PCL's writer pads binary files to a page boundary, so
    // trailing bytes are normal.
    if (available < declared * step) count_mismatch(path, declared, available / step);
    status = reader.readBodyBinary(data, h.blob, h.version, false, static_cast<unsigned>(h.offset));
  }
  if (status < 0) throw Error(path + ": corrupt PCD data (PCL could not decode the body)");
  return encoding;
}

// A compressed body is read without PCL's header parser, which allocates every declared byte of
// every point: the declarations give the layout, and only the fields lmk reads are kept.
CloudFile read_compressed_pcd(const std::string& path, const std::string& bytes,
                              const CheckedHeader& checked) {
  const Declarations& d = checked.says;
  if (d.types.size() != d.fields) {
    throw Error(path + ": header lists " + std::to_string(d.fields) + " fields but " +
                std::to_string(d.types.size()) + " types");
  }
  std::vector<PcdField> fields;
  std::vector<RecordField> named;
  for (std::size_t f = 0; f < d.fields; ++f) {
    const long long count = d.counts.empty() ? 1 : d.counts[f];
    fields.push_back({d.names[f], static_cast<std::size_t>(d.sizes[f]),
                      static_cast<std::size_t>(count), d.types[f][0]});
    named.push_back({d.names[f], 0, 0});
  }
  require_xyz_fields(named, path);  // before decoding anything
  // PCL's rules: WIDTH (or else POINTS) points a row, HEIGHT (or else 1) rows, and POINTS, when
  // given, their product.
  const long long width = d.width >= 0 ? d.width : d.points;
  const long long height = d.height >= 0 ? d.height : 1;
  if (width < 0) throw Error(path + ": not a valid PCD file (its header gives no WIDTH or POINTS)");
  if (d.points >= 0 && width * height != d.points) inconsistent_points(path, d);
  CloudFile file;
  file.encoding = Encoding::kBinaryCompressed;
  for (const std::string& name : d.names) {
    if (name != "_") file.fields.push_back(name);
  }
  const auto* body = reinterpret_cast<const unsigned char*>(bytes.data()) + checked.offset;
  const pcl::PCLPointCloud2 blob =
      read_compressed_body(path, body, bytes.size() - checked.offset, fields,
                           static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height));
  file.cloud = from_pcl(blob, path);
  if (d.viewpoint.size() == 7) {
    const std::vector<double>& v = d.viewpoint;
    sensor_from_pcl(Eigen::Vector4d(v[0], v[1], v[2], 0.0).cast<float>(),
                    Eigen::Quaterniond(v[3], v[4], v[5], v[6]).cast<float>(), file.cloud);
  }
  return file;
}

}  // namespace

CloudFile read_pcd(const std::string& path, const std::string& bytes, std::size_t max_points) {
  const CheckedHeader checked = check_pcd_header(path, bytes, max_points);
  if (checked.says.data == "binary_compressed") return read_compressed_pcd(path, bytes, checked);
  pcl::PCDReader reader;
  PcdHeader h = read_pcd_header(reader, path, bytes, checked);
  CloudFile file;
  file.fields = field_names(h.blob);
  require_xyz(h.blob, path);  // before decoding anything
  file.encoding = read_pcd_body(reader, path, bytes, h);
  file.cloud = from_pcl(h.blob, path);
  sensor_from_pcl(h.origin, h.orientation, file.cloud);
  return file;
}

void write_pcd(const std::filesystem::path& file, const PointCloud& cloud, Encoding encoding) {
  const auto [blob, origin, orientation] = to_pcl(cloud);
  pcl::PCDWriter writer;
  int status = 0;
  switch (encoding) {
    case Encoding::kAscii:
      // 9 significant digits round-trip any float exactly.
      status = writer.writeASCII(file.string(), blob, origin, orientation, 9);
      break;
    case Encoding::kBinary:
      status = writer.writeBinary(file.string(), blob, origin, orientation);
      break;
    case Encoding::kBinaryCompressed:
      status = writer.writeBinaryCompressed(file.string(), blob, origin, orientation);
      break;
  }
  if (status < 0) throw Error(file.string() + ": PCL could not write the PCD file");
}

}  // namespace lmk::detail
