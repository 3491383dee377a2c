// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/ros/cloud_conversion.h"

#include <cstring>
#include <limits>
#include <optional>

#include "lmk/geometry/error.h"

namespace lmk::ros1 {
namespace {

using sensor_msgs::PointField;

std::optional<PointField> find_field(const sensor_msgs::PointCloud2& msg, const std::string& name) {
  for (const PointField& field : msg.fields) {
    if (field.name == name) return field;
  }
  return std::nullopt;
}

std::size_t datatype_size(std::uint8_t datatype) {
  switch (datatype) {
    case PointField::INT8:
    case PointField::UINT8:
      return 1;
    case PointField::INT16:
    case PointField::UINT16:
      return 2;
    case PointField::INT32:
    case PointField::UINT32:
    case PointField::FLOAT32:
      return 4;
    case PointField::FLOAT64:
      return 8;
    default:
      return 0;
  }
}

/// A field that lies within each point's `point_step` bytes, of one of `allowed` types.
PointField checked_field(const sensor_msgs::PointCloud2& msg, const PointField& field,
                         std::initializer_list<std::uint8_t> allowed, const std::string& what) {
  bool type_ok = false;
  for (std::uint8_t t : allowed) type_ok = type_ok || field.datatype == t;
  if (!type_ok) {
    throw Error(what + ": field '" + field.name +
                "' has an unsupported type (PointField datatype " + std::to_string(field.datatype) +
                ")");
  }
  if (field.offset + datatype_size(field.datatype) > msg.point_step) {
    throw Error(what + ": field '" + field.name + "' lies beyond the point step (" +
                std::to_string(msg.point_step) + " bytes)");
  }
  return field;
}

float read_coordinate(const std::uint8_t* point, const PointField& field) {
  if (field.datatype == PointField::FLOAT64) {
    double v;
    std::memcpy(&v, point + field.offset, sizeof v);
    return static_cast<float>(v);
  }
  float v;
  std::memcpy(&v, point + field.offset, sizeof v);
  return v;
}

std::int32_t read_label(const std::uint8_t* point, const PointField& field) {
  std::int32_t v;  // INT32 and UINT32 share the bytes; labels are small
  std::memcpy(&v, point + field.offset, sizeof v);
  return v;
}

/// PCL's packed colour: 0xAARRGGBB in a 32-bit field (a FLOAT32 in most drivers, read as bits).
Color read_color(const std::uint8_t* point, const PointField& field, bool has_alpha) {
  std::uint32_t packed;
  std::memcpy(&packed, point + field.offset, sizeof packed);
  Color c;
  c.r = static_cast<std::uint8_t>((packed >> 16) & 0xff);
  c.g = static_cast<std::uint8_t>((packed >> 8) & 0xff);
  c.b = static_cast<std::uint8_t>(packed & 0xff);
  c.a = has_alpha ? static_cast<std::uint8_t>(packed >> 24) : 255;
  return c;
}

}  // namespace

PointCloud from_ros(const sensor_msgs::PointCloud2& msg, const std::string& what) {
  if (msg.is_bigendian) throw Error(what + ": big-endian point data is not supported");
  const std::uint64_t count = std::uint64_t{msg.width} * msg.height;
  if (msg.point_step == 0 && count > 0) throw Error(what + ": point_step is 0");
  if (std::uint64_t{msg.row_step} < std::uint64_t{msg.width} * msg.point_step) {
    throw Error(what + ": row_step " + std::to_string(msg.row_step) + " is less than width x " +
                "point_step (" + std::to_string(std::uint64_t{msg.width} * msg.point_step) + ")");
  }
  if (std::uint64_t{msg.row_step} * msg.height > msg.data.size()) {
    throw Error(what + ": holds " + std::to_string(msg.data.size()) + " bytes, but its header " +
                "declares " + std::to_string(std::uint64_t{msg.row_step} * msg.height));
  }
  PointField axes[3];
  const char* names[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    const std::optional<PointField> field = find_field(msg, names[i]);
    if (!field) throw Error(what + ": has no '" + names[i] + "' field");
    axes[i] = checked_field(msg, *field, {PointField::FLOAT32, PointField::FLOAT64}, what);
  }
  std::optional<PointField> color = find_field(msg, "rgb");
  const bool has_alpha = !color && find_field(msg, "rgba");
  if (has_alpha) color = find_field(msg, "rgba");
  if (color) {
    color = checked_field(msg, *color, {PointField::FLOAT32, PointField::UINT32}, what);
  }
  std::optional<PointField> label = find_field(msg, "label");
  if (label) label = checked_field(msg, *label, {PointField::INT32, PointField::UINT32}, what);

  PointCloud cloud;
  cloud.points.reserve(count);
  if (color) cloud.colors.reserve(count);
  if (label) cloud.labels.reserve(count);
  for (std::uint32_t row = 0; row < msg.height; ++row) {
    const std::uint8_t* row_start = msg.data.data() + std::size_t{row} * msg.row_step;
    for (std::uint32_t col = 0; col < msg.width; ++col) {
      const std::uint8_t* point = row_start + std::size_t{col} * msg.point_step;
      cloud.points.emplace_back(read_coordinate(point, axes[0]), read_coordinate(point, axes[1]),
                                read_coordinate(point, axes[2]));
      if (color) cloud.colors.push_back(read_color(point, *color, has_alpha));
      if (label) cloud.labels.push_back(read_label(point, *label));
    }
  }
  // A ROS cloud with height 1 is unorganised, as in lmk.
  cloud.width = msg.width;
  cloud.height = msg.height;
  if (cloud.height <= 1) cloud.set_unorganized();
  return cloud;
}

sensor_msgs::PointCloud2 to_ros(const PointCloud& cloud, const std::string& frame_id) {
  cloud.validate("the cloud to publish");
  sensor_msgs::PointCloud2 msg;
  msg.header.frame_id = frame_id;
  msg.is_bigendian = false;
  const auto add_field = [&msg](const char* name, std::uint8_t datatype) {
    PointField field;
    field.name = name;
    field.offset = msg.point_step;
    field.datatype = datatype;
    field.count = 1;
    msg.fields.push_back(field);
    msg.point_step += static_cast<std::uint32_t>(datatype_size(datatype));
    return field;
  };
  const PointField x = add_field("x", PointField::FLOAT32);
  add_field("y", PointField::FLOAT32);
  add_field("z", PointField::FLOAT32);
  // Colour as PCL packs it: 0xAARRGGBB in a FLOAT32 field named rgb (what RViz colours by).
  const std::optional<PointField> rgb =
      cloud.has_colors() ? std::optional(add_field("rgb", PointField::FLOAT32)) : std::nullopt;
  const std::optional<PointField> label =
      cloud.has_labels() ? std::optional(add_field("label", PointField::INT32)) : std::nullopt;

  msg.width = cloud.is_organized() ? cloud.width : static_cast<std::uint32_t>(cloud.size());
  msg.height = cloud.is_organized() ? cloud.height : 1;
  msg.row_step = msg.width * msg.point_step;
  msg.data.assign(std::size_t{msg.row_step} * msg.height, 0);
  bool dense = true;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    std::uint8_t* point = msg.data.data() + i * msg.point_step;
    const Eigen::Vector3f& p = cloud.points[i];
    std::memcpy(point + x.offset, p.data(), 3 * sizeof(float));
    dense = dense && is_finite(p);
    if (rgb) {
      const Color& c = cloud.colors[i];
      const std::uint32_t packed = std::uint32_t{c.a} << 24 | std::uint32_t{c.r} << 16 |
                                   std::uint32_t{c.g} << 8 | std::uint32_t{c.b};
      std::memcpy(point + rgb->offset, &packed, sizeof packed);
    }
    if (label) std::memcpy(point + label->offset, &cloud.labels[i], sizeof(std::int32_t));
  }
  msg.is_dense = dense;
  return msg;
}

}  // namespace lmk::ros1
