// PLY through PCL's reader and writer. lmk parses the header itself first, to reject garbage and
// truncated files with a clear message before PCL's parser sees them.

#include <pcl/io/ply_io.h>

#include <sstream>

#include "geometry/detail/formats.h"
#include "geometry/detail/pcl_conversion.h"
#include "geometry/error.h"

namespace lmk::detail {
namespace {

struct PlyHeader {
  Encoding encoding = Encoding::kAscii;
  std::size_t vertices = 0;
  std::size_t vertex_stride = 0;  // bytes per binary vertex; 0 when a vertex property is a list
  bool vertex_first = false;      // the vertex element comes first, so its data starts the body
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

PlyHeader parse_header(const std::string& path, const std::string& bytes) {
  if (bytes.compare(0, 3, "ply") != 0) throw Error(path + ": not a PLY file (no 'ply' magic line)");
  const std::size_t end = bytes.find("end_header");
  if (end == std::string::npos) throw Error(path + ": not a valid PLY file (no end_header line)");
  PlyHeader h;
  const std::size_t newline = bytes.find('\n', end);
  h.body_offset = newline == std::string::npos ? bytes.size() : newline + 1;

  std::istringstream in(bytes.substr(0, end));
  std::string line, current_element;
  bool format_seen = false, vertex_has_list = false;
  int element_index = 0;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "format") {
      std::string kind;
      words >> kind;
      format_seen = true;
      if (kind == "ascii") {
        h.encoding = Encoding::kAscii;
      } else if (kind == "binary_little_endian" || kind == "binary_big_endian") {
        h.encoding = Encoding::kBinary;
      } else {
        throw Error(path + ": unknown PLY format '" + kind + "'");
      }
    } else if (key == "element") {
      std::size_t count = 0;
      words >> current_element >> count;
      if (!words) throw Error(path + ": malformed PLY element line: '" + line + "'");
      if (current_element == "vertex") {
        h.vertices = count;
        h.vertex_first = element_index == 0;
      }
      ++element_index;
    } else if (key == "property" && current_element == "vertex") {
      std::string type;
      words >> type;
      if (type == "list") {
        vertex_has_list = true;
        continue;
      }
      const std::size_t size = ply_type_size(type);
      if (size == 0) throw Error(path + ": unknown PLY property type '" + type + "'");
      h.vertex_stride += size;
    }
  }
  if (vertex_has_list) h.vertex_stride = 0;
  if (!format_seen) throw Error(path + ": not a valid PLY file (no format line)");
  return h;
}

}  // namespace

CloudFile read_ply(const std::string& path, const std::string& bytes) {
  const PlyHeader h = parse_header(path, bytes);
  const std::size_t available = bytes.size() - std::min(h.body_offset, bytes.size());
  if (h.vertex_first) {
    const std::size_t held = h.encoding == Encoding::kAscii ? count_data_rows(bytes, h.body_offset)
                             : h.vertex_stride > 0          ? available / h.vertex_stride
                                                            : h.vertices;  // size unknown: lists
    if (held < h.vertices) {
      throw Error(path + ": truncated: header declares " + std::to_string(h.vertices) +
                  " vertices but the data holds " + std::to_string(held));
    }
  }
  pcl::PLYReader reader;
  pcl::PCLPointCloud2 blob;
  Eigen::Vector4f origin = Eigen::Vector4f::Zero();
  Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();
  int version = 0;
  if (reader.read(path, blob, origin, orientation, version) < 0) {
    throw Error(path + ": corrupt PLY data (PCL could not decode it)");
  }
  CloudFile file;
  file.encoding = h.encoding;
  file.fields = field_names(blob);
  file.cloud = from_pcl(blob, path);
  sensor_from_pcl(origin, orientation, file.cloud);
  return file;
}

void write_ply(const std::filesystem::path& file, const PointCloud& cloud, Encoding encoding) {
  const pcl::PCLPointCloud2 blob = to_pcl(cloud);
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  sensor_to_pcl(cloud, origin, orientation);
  pcl::PLYWriter writer;
  // use_camera = true stores the sensor pose in PCL's "camera" element, which PLYReader reads back.
  const int status =
      writer.write(file.string(), blob, origin, orientation, encoding != Encoding::kAscii, true);
  if (status < 0) throw Error(file.string() + ": PCL could not write the PLY file");
}

}  // namespace lmk::detail
