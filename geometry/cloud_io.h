// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Reading and writing point clouds: PCD (ascii, binary, binary_compressed), PLY (ascii, binary)
// and plain XYZ text. The format follows the file extension.
//
// Every problem with a file is an lmk::Error whose message starts with the file's path and says
// what is wrong: a missing file, an unknown extension, a truncated or garbage file, a header
// that disagrees with the data, no x/y/z fields, or no finite point at all. Writes are atomic.

#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/error.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk {

enum class CloudFormat { kPcd, kPly, kXyz };

/// The most points a cloud file may declare: ten times a 5-million-point scene, about 1.4 GB of
/// points in memory. A header over it is refused before anything is allocated.
inline constexpr std::size_t kMaxCloudPoints = 50'000'000;
/// The most bytes one point of a PCD file may declare (its fields' SIZE x COUNT summed).
inline constexpr std::size_t kMaxPcdPointBytes = 1 << 16;

/// How a file stores its data. PLY and XYZ use kAscii / kBinary; kBinaryCompressed is PCD's LZF.
enum class Encoding { kAscii, kBinary, kBinaryCompressed };

/// A cloud as read from disk, with what the file said about itself.
struct CloudFile {
  PointCloud cloud;
  CloudFormat format = CloudFormat::kPcd;
  Encoding encoding = Encoding::kBinary;
  /// The file's field (property) names in file order, without padding fields such as "_".
  std::vector<std::string> fields;
};

/// The format for a path's extension (case-insensitive .pcd, .ply, .xyz); throws lmk::Error
/// naming the supported extensions otherwise.
CloudFormat format_from_path(const std::string& path);

/// A cloud with more points than its reader was allowed: refused from the header before anything
/// is decoded, or as an XYZ file's rows are read, never after a whole oversized cloud is in memory.
struct CloudTooLarge : Error {
  using Error::Error;
};

/// Reads any supported file. Organised clouds keep width x height and their NaN points. More
/// than `max_points` points: CloudTooLarge.
CloudFile read_cloud_file(const std::string& path, std::size_t max_points = kMaxCloudPoints);
/// Reads any supported file and returns the cloud alone.
PointCloud read_cloud(const std::string& path, std::size_t max_points = kMaxCloudPoints);

/// What a PCD or PLY file's header declares, read from its first 64 KB without decoding anything:
/// what a caller that budgets memory (lmk serve) prices a file at before reading it.
struct DeclaredCloud {
  std::size_t points = 0;
  /// The bytes a point takes in the reader's working copy, beside the cloud it returns: PCD's
  /// declared fields whole for an ASCII or binary body (PCL decodes them all), only the fields lmk
  /// reads for a compressed one; 0 where the header does not say (PLY).
  std::size_t decoded_point_bytes = 0;
};
/// Nothing for XYZ, which has no header, or when the header gives no point count.
std::optional<DeclaredCloud> declared_cloud(const std::string& path);

/// What reading a file of `file_bytes` that may hold `points` points takes at its peak, bytes: its
/// bytes twice (read whole, and copied once more by PCL's ASCII reader: an ASCII PCD of a million
/// points took 107 MB for a 36 MB file); per point, the cloud (22 bytes measured for a binary PCD)
/// or an XYZ file's rows growing their vector (53), rounded up to 80; and the reader's working copy
/// of each point (DeclaredCloud::decoded_point_bytes): a compressed PCD that declares 4,012 bytes
/// a point is priced at the 12 it keeps, an ASCII one at all 4,012. UploadPrice.* measures it.
std::size_t cloud_read_price(std::size_t file_bytes, std::size_t points,
                             std::size_t decoded_point_bytes);
/// The fewest bytes a point of an XYZ file takes ("0 0 0\n"): what bounds its points unread.
inline constexpr std::size_t kLeastXyzPointBytes = 6;
/// The same for the file at `path`, from its size and header (declared_cloud()); an XYZ file is
/// priced at its size over kLeastXyzPointBytes a point, its shortest row.
std::size_t cloud_read_price(const std::string& path);

struct WriteOptions {
  /// PCD: kBinaryCompressed (default), kBinary or kAscii. PLY: kBinary (default) or kAscii;
  /// kBinaryCompressed means kBinary for PLY. XYZ is always text.
  Encoding encoding = Encoding::kBinaryCompressed;
};

/// Writes the cloud in the format of the path's extension, atomically. Normals, colours, labels,
/// the width x height organisation and the sensor pose are kept where the format can hold them
/// (XYZ holds coordinates only).
void write_cloud(const std::string& path, const PointCloud& cloud,
                 const WriteOptions& options = {});

const char* to_string(CloudFormat format);
const char* to_string(Encoding encoding);

}  // namespace lmk
