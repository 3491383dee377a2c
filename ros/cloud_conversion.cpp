// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/ros/cloud_conversion.h"

#include <cstring>
#include <optional>

#include "lmk/geometry/error.h"
#include "lmk/geometry/point_records.h"

namespace lmk::ros1 {
namespace {

using sensor_msgs::PointField;

}  // namespace

// A thin adapter to lmk's one reader of packed points (geometry/point_records.h), which PCD and
// PLY files go through too.
PointCloud from_ros(const sensor_msgs::PointCloud2& msg, const std::string& what) {
  if (msg.is_bigendian) throw Error(what + ": big-endian point data is not supported");
  PointRecords records;
  for (const PointField& f : msg.fields) records.fields.push_back({f.name, f.offset, f.datatype});
  records.width = msg.width;
  records.height = msg.height;
  records.point_step = msg.point_step;
  records.row_step = msg.row_step;
  records.data = msg.data.data();
  records.bytes = msg.data.size();
  PointCloud cloud = decode_point_records(records, what);
  if (cloud.height <= 1) cloud.set_unorganized();  // a ROS cloud of height 1 is unorganised
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
    msg.point_step += static_cast<std::uint32_t>(point_datatype_bytes(datatype));
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
      const std::uint32_t packed = pack_point_color(cloud.colors[i]);
      std::memcpy(point + rgb->offset, &packed, sizeof packed);
    }
    if (label) std::memcpy(point + label->offset, &cloud.labels[i], sizeof(std::int32_t));
  }
  msg.is_dense = dense;
  return msg;
}

}  // namespace lmk::ros1
