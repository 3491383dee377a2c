// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Decoding packed point records: the layout that PCL's PCLPointCloud2 (behind every PCD and PLY
// file lmk reads) and ROS's sensor_msgs/PointCloud2 share. Both describe a point as named fields
// at byte offsets within a fixed point step, with the same datatype codes, and a frame as rows of
// such points; this is the one reader of that layout, and each of them is a thin adapter to it
// (geometry/detail/pcl_conversion.h, ros/cloud_conversion.h).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "lmk/geometry/point_cloud.h"

namespace lmk {

/// The datatype codes of PCL's PCLPointField and ROS's sensor_msgs/PointField (equal in both).
enum class PointDatatype : std::uint8_t {
  kInt8 = 1,
  kUint8 = 2,
  kInt16 = 3,
  kUint16 = 4,
  kInt32 = 5,
  kUint32 = 6,
  kFloat32 = 7,
  kFloat64 = 8,
};

/// One field of a point record.
struct RecordField {
  std::string name;
  std::uint32_t offset = 0;   ///< bytes from the start of a point
  std::uint8_t datatype = 0;  ///< a PointDatatype code; anything else is refused when read
};

/// Rows of `height` x `width` points, each `point_step` bytes, rows `row_step` bytes apart, in
/// little-endian byte order.
struct PointRecords {
  std::vector<RecordField> fields;
  std::uint32_t width = 0, height = 0;
  std::uint32_t point_step = 0, row_step = 0;
  const std::uint8_t* data = nullptr;
  std::size_t bytes = 0;
};

/// Reads x/y/z (any numeric datatype), normal_x/y/z, "rgba" or else "rgb" (PCL's packed
/// 0xAARRGGBB colour: read as bits from a 32-bit field, as a whole number from any other) and
/// "label"; every other field is ignored. The cloud keeps the records' rows (organised when
/// height > 1) and NaN points. Throws lmk::Error naming `where` when x, y or z is missing, a field
/// read has an unknown datatype or lies beyond the point step, or the rows need more bytes than
/// there are.
PointCloud decode_point_records(const PointRecords& records, const std::string& where);

/// Whether decode_point_records reads a field of this name: a reader that must not hold a whole
/// file (PCD's compressed body) keeps these and drops the rest.
bool is_read_field(const std::string& name);

/// Throws lmk::Error naming `where` and the fields there are, unless x, y and z are among them.
void require_xyz_fields(const std::vector<RecordField>& fields, const std::string& where);

/// The number of bytes of one value of `datatype`; 0 for a code that is no PointDatatype.
std::size_t point_datatype_bytes(std::uint8_t datatype);

/// PCL's packed colour 0xAARRGGBB; `has_alpha` false reads the top byte as opaque.
Color unpack_point_color(std::uint32_t packed, bool has_alpha);
std::uint32_t pack_point_color(const Color& c);

}  // namespace lmk
