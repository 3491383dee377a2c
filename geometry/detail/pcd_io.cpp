// PCD through PCL's reader and writer. PCL parses the header and decodes the body; before it
// touches the body, lmk checks that the data really holds the points the header declares, because
// PCL's binary decoders trust the header and would read past the end of a truncated file.

#include <pcl/io/pcd_io.h>

#include <cstring>
#include <sstream>

#include "geometry/detail/formats.h"
#include "geometry/detail/pcl_conversion.h"
#include "geometry/error.h"

namespace lmk::detail {
namespace {

// Byte offset just past the "DATA ..." header line, or npos when there is none.
std::size_t body_offset(const std::string& bytes) {
  std::size_t line = 0;
  while (line < bytes.size()) {
    const std::size_t end = bytes.find('\n', line);
    if (bytes.compare(line, 4, "DATA") == 0)
      return end == std::string::npos ? bytes.size() : end + 1;
    if (end == std::string::npos) break;
    line = end + 1;
  }
  return std::string::npos;
}

std::size_t count_ascii_rows(const std::string& bytes, std::size_t offset) {
  std::size_t rows = 0;
  std::istringstream body(bytes.substr(offset));
  std::string line;
  while (std::getline(body, line)) {
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first != std::string::npos && line[first] != '#') ++rows;
  }
  return rows;
}

[[noreturn]] void count_mismatch(const std::string& path, std::size_t declared, std::size_t held) {
  throw Error(path + (held < declared ? ": truncated: header" : ": header") + " declares " +
              std::to_string(declared) + " points but the data holds " + std::to_string(held));
}

}  // namespace

CloudFile read_pcd(const std::string& path, const std::string& bytes) {
  pcl::PCDReader reader;
  pcl::PCLPointCloud2 blob;
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int version = 0, data_type = 0;
  unsigned int pcl_data_idx = 0;
  std::istringstream header(bytes);
  const std::size_t offset = body_offset(bytes);
  if (offset == std::string::npos ||
      reader.readHeader(header, blob, origin, orientation, version, data_type, pcl_data_idx) < 0) {
    throw Error(path + ": not a valid PCD file (its header could not be parsed)");
  }
  CloudFile file;
  file.fields = field_names(blob);
  require_xyz(blob, path);  // before decoding anything
  if (blob.width == 0 && blob.height == 0) blob.height = 1;
  const std::size_t declared = static_cast<std::size_t>(blob.width) * blob.height;
  const std::size_t step = blob.point_step;
  const std::size_t available = bytes.size() - std::min(offset, bytes.size());
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());

  int status = 0;
  if (data_type == 0) {
    file.encoding = Encoding::kAscii;
    const std::size_t rows = count_ascii_rows(bytes, offset);
    if (rows != declared) count_mismatch(path, declared, rows);
    std::istringstream body(bytes);
    body.seekg(static_cast<std::streamoff>(offset));
    status = reader.readBodyASCII(body, blob, version);
  } else if (data_type == 1) {
    file.encoding = Encoding::kBinary;
    if (step == 0) throw Error(path + ": header declares fields of zero size");
    if (available < declared * step || available >= (declared + 1) * step) {
      count_mismatch(path, declared, available / step);
    }
    status = reader.readBodyBinary(data, blob, version, false, static_cast<unsigned>(offset));
  } else {
    file.encoding = Encoding::kBinaryCompressed;
    // The compressed block starts with its compressed and uncompressed sizes (uint32 each).
    std::uint32_t sizes[2] = {0, 0};
    if (available < sizeof(sizes)) count_mismatch(path, declared, 0);
    std::memcpy(sizes, data + offset, sizeof(sizes));
    if (available - sizeof(sizes) < sizes[0]) {
      throw Error(path + ": truncated: the compressed block declares " + std::to_string(sizes[0]) +
                  " bytes but the file holds " + std::to_string(available - sizeof(sizes)));
    }
    if (step == 0 || sizes[1] != declared * step) {
      count_mismatch(path, declared, step == 0 ? 0 : sizes[1] / step);
    }
    status = declared == 0
                 ? 0
                 : reader.readBodyBinary(data, blob, version, true, static_cast<unsigned>(offset));
  }
  if (status < 0) throw Error(path + ": corrupt PCD data (PCL could not decode the body)");

  file.cloud = from_pcl(blob, path);
  sensor_from_pcl(origin, orientation, file.cloud);
  return file;
}

void write_pcd(const std::filesystem::path& file, const PointCloud& cloud, Encoding encoding) {
  const pcl::PCLPointCloud2 blob = to_pcl(cloud);
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  sensor_to_pcl(cloud, origin, orientation);
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
