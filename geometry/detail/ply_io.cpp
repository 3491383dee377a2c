// SPDX-License-Identifier: BSD-3-Clause
// PLY through PCL's reader and writer. lmk parses the header itself first, to reject garbage and
// truncated files with a clear message before PCL's parser sees them, and to read the sensor pose
// that PCL writes but does not read back.

#include <pcl/io/ply_io.h>

#include <cstring>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

#include "lmk/geometry/detail/formats.h"
#include "lmk/geometry/detail/pcl_conversion.h"
#include "lmk/geometry/error.h"

namespace lmk::detail {
namespace {

struct PlyProperty {
  std::string name, type;
  bool is_list = false;
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  Encoding encoding = Encoding::kAscii;
  bool big_endian = false;
  std::vector<PlyElement> elements;
  std::size_t body_offset = 0;
};

std::size_t ply_type_size(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" ||
      type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

// Bytes per binary entry of an element, or 0 when it has a list property (variable size).
std::size_t element_stride(const PlyElement& e) {
  std::size_t stride = 0;
  for (const PlyProperty& p : e.properties) {
    if (p.is_list) return 0;
    stride += ply_type_size(p.type);
  }
  return stride;
}

PlyHeader parse_header(const std::string& path, const std::string& bytes) {
  if (bytes.compare(0, 3, "ply") != 0) throw Error(path + ": not a PLY file (no 'ply' magic line)");
  // The header ends at the first line that is exactly "end_header", as PCL's parser reads it: a
  // line merely containing it had lmk and PCL see different headers (found by fuzzing).
  std::size_t end = std::string::npos;
  for (std::size_t line = 0; line < bytes.size();) {
    const std::size_t newline = bytes.find('\n', line);
    std::string text = bytes.substr(line, newline == std::string::npos ? newline : newline - line);
    while (!text.empty() && (text.back() == '\r' || text.back() == ' ')) text.pop_back();
    if (text == "end_header") {
      end = line;
      break;
    }
    if (newline == std::string::npos) break;
    line = newline + 1;
  }
  if (end == std::string::npos) throw Error(path + ": not a valid PLY file (no end_header line)");
  PlyHeader h;
  const std::size_t newline = bytes.find('\n', end);
  h.body_offset = newline == std::string::npos ? bytes.size() : newline + 1;

  std::istringstream in(bytes.substr(0, end));
  std::string line;
  bool format_seen = false;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "format") {
      std::string kind;
      words >> kind;
      format_seen = true;
      h.encoding = kind == "ascii" ? Encoding::kAscii : Encoding::kBinary;
      h.big_endian = kind == "binary_big_endian";
      if (kind != "ascii" && kind != "binary_little_endian" && !h.big_endian) {
        throw Error(path + ": unknown PLY format '" + printable(kind) + "'");
      }
    } else if (key == "element") {
      PlyElement e;
      std::string count;
      words >> e.name >> count;
      const std::optional<long long> n = header_count(count);
      if (!words || !n) {
        throw Error(path + ": malformed PLY element line: '" + printable(line) + "'");
      }
      e.count = static_cast<std::size_t>(*n);
      if (e.count > kMaxCloudPoints) {
        throw Error(path + ": header declares " + count + " " + printable(e.name) +
                    " entries, over lmk's limit of " + std::to_string(kMaxCloudPoints) + " points");
      }
      h.elements.push_back(e);
    } else if (!key.empty() && key != "ply" && key != "format" && key != "comment" &&
               key != "obj_info" && key != "element" && key != "property") {
      throw Error(path + ": unknown PLY header line '" + printable(line) + "'");
    } else if (key == "property" && !h.elements.empty()) {
      PlyProperty p;
      words >> p.type;
      p.is_list = p.type == "list";
      if (p.is_list) {
        std::string count_type, item_type;
        words >> count_type >> item_type;
      } else if (ply_type_size(p.type) == 0) {
        throw Error(path + ": unknown PLY property type '" + printable(p.type) + "'");
      }
      words >> p.name;
      h.elements.back().properties.push_back(p);
    }
  }
  if (!format_seen) throw Error(path + ": not a valid PLY file (no format line)");
  return h;
}

// Reads one scalar property of the given type at `p`, honouring the file's byte order.
double load_binary(const char* p, const std::string& type, bool big_endian) {
  char buffer[8];
  const std::size_t size = ply_type_size(type);
  for (std::size_t i = 0; i < size; ++i) buffer[i] = p[big_endian ? size - 1 - i : i];
  const auto as = [&](auto v) {
    std::memcpy(&v, buffer, sizeof(v));
    return static_cast<double>(v);
  };
  if (type == "float" || type == "float32") return as(float{});
  if (type == "double" || type == "float64") return as(double{});
  if (type == "int" || type == "int32") return as(std::int32_t{});
  if (type == "uint" || type == "uint32") return as(std::uint32_t{});
  if (type == "short" || type == "int16") return as(std::int16_t{});
  if (type == "ushort" || type == "uint16") return as(std::uint16_t{});
  if (type == "char" || type == "int8") return as(std::int8_t{});
  return as(std::uint8_t{});
}

// The sensor pose from the "camera" element that PCL's PLY writer adds (view point and axes) but
// PCL's reader does not return. Read only when every element before it has a fixed size, which is
// how PCL lays it out; otherwise the pose stays the identity.
std::optional<Eigen::Isometry3d> read_camera(const PlyHeader& h, const std::string& bytes) {
  std::size_t offset = h.body_offset, rows_before = 0;
  const PlyElement* camera = nullptr;
  for (const PlyElement& e : h.elements) {
    if (e.name == "camera") {
      camera = &e;
      break;
    }
    if (e.count == 0) continue;  // PCL writes an empty "face" element with no properties
    const std::size_t stride = element_stride(e);
    if (stride == 0) return std::nullopt;
    offset += e.count * stride;
    rows_before += e.count;
  }
  if (camera == nullptr || camera->count < 1 || element_stride(*camera) == 0) return std::nullopt;

  std::map<std::string, double> values;
  if (h.encoding == Encoding::kAscii) {
    std::istringstream body(bytes.substr(h.body_offset));
    std::string line;
    for (std::size_t row = 0; row <= rows_before && std::getline(body, line);) {
      if (line.find_first_not_of(" \t\r") != std::string::npos) ++row;
    }
    std::istringstream words(line);
    for (const PlyProperty& p : camera->properties) words >> values[p.name];
    if (!words) return std::nullopt;
  } else {
    if (offset + element_stride(*camera) > bytes.size()) return std::nullopt;
    for (const PlyProperty& p : camera->properties) {
      values[p.name] = load_binary(bytes.data() + offset, p.type, h.big_endian);
      offset += ply_type_size(p.type);
    }
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  Eigen::Matrix3d axes;
  const char* names[3][3] = {{"x_axisx", "x_axisy", "x_axisz"},
                             {"y_axisx", "y_axisy", "y_axisz"},
                             {"z_axisx", "z_axisy", "z_axisz"}};
  for (int axis = 0; axis < 3; ++axis) {
    for (int c = 0; c < 3; ++c) {
      const auto it = values.find(names[axis][c]);
      if (it == values.end()) return std::nullopt;
      axes(axis, c) = it->second;  // PCL's writer stores the rotation's rows as "axes"
    }
  }
  T.translation() << values["view_px"], values["view_py"], values["view_pz"];
  // Stored as floats: re-orthonormalise through a quaternion.
  const Eigen::Quaterniond q(axes);
  if (!T.translation().allFinite() || !q.coeffs().allFinite() || q.norm() < 1e-6) {
    return std::nullopt;
  }
  T.linear() = q.normalized().toRotationMatrix();
  return T;
}

// The colour channel a property is to PCL's reader (0 red, 1 green, 2 blue, 3 alpha), or -1: PCL
// packs 8-bit red, green, blue and alpha properties into one colour field.
int color_channel(const PlyProperty& p) {
  if (p.type != "uchar" && p.type != "uint8") return -1;
  const std::string name = p.name.rfind("diffuse_", 0) == 0 ? p.name.substr(8) : p.name;
  const char* channels[] = {"red", "green", "blue", "alpha"};
  for (int c = 0; c < 4; ++c) {
    if (name == channels[c]) return c;
  }
  return -1;
}

// PCL's reader asserts (and so aborts the process) on vertex properties it cannot place: a list,
// and colour channels other than red, green, blue (alpha) one after another, since it writes the
// colour when it meets blue, at the place where it met red (a fuzzed file with green and blue
// alone aborted). Refused here first, with repeated names, which no writer produces.
void check_vertex_properties(const std::string& path, const PlyElement& vertex) {
  // The colour properties' channels in order, and where the first of them stands.
  std::vector<int> channels;
  std::size_t first_color = 0;
  for (std::size_t i = 0; i < vertex.properties.size(); ++i) {
    const PlyProperty& p = vertex.properties[i];
    if (p.is_list) {
      throw Error(path + ": vertex property '" + printable(p.name) +
                  "' is a list; lmk reads scalar vertex properties only");
    }
    for (std::size_t k = 0; k < i; ++k) {
      if (vertex.properties[k].name == p.name) {
        throw Error(path + ": vertex property '" + printable(p.name) + "' is declared twice");
      }
    }
    const int channel = color_channel(p);
    if (channel < 0) continue;
    if (channels.empty()) first_color = i;
    // One after another, in channel order: the channel is its distance from the first.
    channels.push_back(i - first_color == static_cast<std::size_t>(channel) ? channel : -1);
  }
  const std::vector<int> rgb = {0, 1, 2}, rgba = {0, 1, 2, 3};
  if (!channels.empty() && channels != rgb && channels != rgba) {
    throw Error(path +
                ": vertex colour properties must be red, green and blue (then alpha), one after "
                "another");
  }
}

// An ASCII body holds one line per element entry: the vertices first, then any other element
// (PCL adds a "camera" line). Every row is counted and every vertex row checked, before PCL, which
// would read a row "foo bar baz" as a NaN point and ignore rows beyond the declared count.
void check_ascii_rows(const std::string& path, const PlyHeader& h, const std::string& bytes) {
  const PlyElement& vertex = h.elements.front();
  std::size_t rows_declared = 0;
  for (const PlyElement& e : h.elements) rows_declared += e.count;
  const bool fixed_rows = element_stride(vertex) > 0;  // no list property
  const AsciiBodyScan scan = scan_ascii_body(bytes, h.body_offset, vertex.properties.size(),
                                             fixed_rows ? vertex.count : 0);
  if (scan.rows < vertex.count) {
    throw Error(path + ": truncated: header declares " + std::to_string(vertex.count) +
                " vertices but the data holds " + std::to_string(scan.rows));
  }
  if (!scan.first_problem.empty()) throw Error(path + ": " + scan.first_problem);
  if (scan.rows > rows_declared) {
    throw Error(path + ": header declares " + std::to_string(rows_declared) +
                " data rows but the data holds " + std::to_string(scan.rows));
  }
}

}  // namespace

CloudFile read_ply(const std::string& path, const std::string& bytes, std::size_t max_points) {
  const PlyHeader h = parse_header(path, bytes);
  const std::size_t available = bytes.size() - std::min(h.body_offset, bytes.size());
  for (const PlyElement& e : h.elements) {
    if (e.name != "vertex") continue;
    if (e.count > max_points) too_many_points(path, std::to_string(e.count), max_points);
    check_vertex_properties(path, e);
  }
  // Check the data really holds the vertices, when they come first (as every writer puts them).
  if (!h.elements.empty() && h.elements.front().name == "vertex") {
    const PlyElement& vertex = h.elements.front();
    const std::size_t stride = element_stride(vertex);
    if (h.encoding == Encoding::kAscii) check_ascii_rows(path, h, bytes);
    const std::size_t held = h.encoding == Encoding::kAscii ? vertex.count
                             : stride > 0                   ? available / stride
                                                            : vertex.count;  // lists: unknown
    if (held < vertex.count) {
      throw Error(path + ": truncated: header declares " + std::to_string(vertex.count) +
                  " vertices but the data holds " + std::to_string(held));
    }
  }
  pcl::PLYReader reader;
  pcl::PCLPointCloud2 blob;
  if (reader.read(path, blob) < 0) {
    throw Error(path + ": corrupt PLY data (PCL could not decode it)");
  }
  CloudFile file;
  file.encoding = h.encoding;
  file.fields = field_names(blob);
  file.cloud = from_pcl(blob, path);
  if (const auto T = read_camera(h, bytes)) file.cloud.T_cloud_sensor = *T;
  return file;
}

void write_ply(const std::filesystem::path& file, const PointCloud& cloud, Encoding encoding) {
  const auto [blob, origin, orientation] = to_pcl(cloud);
  pcl::PLYWriter writer;
  // The camera element (use_camera) stores the sensor pose; read_camera() reads it back. ASCII uses
  // 9 significant digits, which round-trip any float exactly (PCL's default of 8 does not).
  const int status = encoding == Encoding::kAscii
                         ? writer.writeASCII(file.string(), blob, origin, orientation, 9, true)
                         : writer.writeBinary(file.string(), blob, origin, orientation, true);
  if (status < 0) throw Error(file.string() + ": PCL could not write the PLY file");
}

}  // namespace lmk::detail
