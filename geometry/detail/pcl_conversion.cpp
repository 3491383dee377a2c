// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/detail/pcl_conversion.h"

#include <algorithm>
#include <cstring>

#include "lmk/geometry/point_records.h"

namespace lmk::detail {
namespace {

using Field = pcl::PCLPointField;

void append_field(pcl::PCLPointCloud2& blob, const std::string& name, std::uint8_t datatype) {
  Field f;
  f.name = name;
  f.offset = blob.point_step;
  f.datatype = datatype;
  f.count = 1;
  blob.fields.push_back(f);
  blob.point_step += 4;  // every field lmk writes is 4 bytes
}

template <typename T>
void store(std::uint8_t* p, T v) {
  std::memcpy(p, &v, sizeof(T));
}

}  // namespace

std::vector<std::string> field_names(const pcl::PCLPointCloud2& blob) {
  std::vector<std::string> names;
  for (const Field& f : blob.fields) {
    if (f.name != "_") names.push_back(f.name);
  }
  return names;
}

namespace {

std::vector<RecordField> record_fields(const pcl::PCLPointCloud2& blob) {
  std::vector<RecordField> fields;
  for (const Field& f : blob.fields) fields.push_back({f.name, f.offset, f.datatype});
  return fields;
}

}  // namespace

void require_xyz(const pcl::PCLPointCloud2& blob, const std::string& path) {
  require_xyz_fields(record_fields(blob), path);
}

// PCL's readers hand over host-order (little-endian) data, and leave row_step 0 for packed rows.
PointCloud from_pcl(const pcl::PCLPointCloud2& blob, const std::string& path) {
  PointRecords records;
  records.fields = record_fields(blob);
  records.width = blob.width;
  records.height = blob.height;
  records.point_step = blob.point_step;
  records.row_step = blob.row_step != 0 ? blob.row_step : blob.width * blob.point_step;
  records.data = blob.data.data();
  records.bytes = blob.data.size();
  return decode_point_records(records, path);
}

PclCloud to_pcl(const PointCloud& cloud) {
  PclCloud out;
  pcl::PCLPointCloud2& blob = out.blob;
  blob.width = cloud.width;
  blob.height = cloud.height;
  blob.is_dense = cloud.count_finite() == cloud.size();
  blob.point_step = 0;
  for (const char* name : {"x", "y", "z"}) append_field(blob, name, Field::FLOAT32);
  if (cloud.has_normals()) {
    for (const char* name : {"normal_x", "normal_y", "normal_z"})
      append_field(blob, name, Field::FLOAT32);
  }
  const bool alpha = std::any_of(cloud.colors.begin(), cloud.colors.end(),
                                 [](const Color& c) { return c.a != 255; });
  if (cloud.has_colors())
    append_field(blob, alpha ? "rgba" : "rgb", alpha ? Field::UINT32 : Field::FLOAT32);
  const bool negative_label =
      std::any_of(cloud.labels.begin(), cloud.labels.end(), [](std::int32_t l) { return l < 0; });
  if (cloud.has_labels())
    append_field(blob, "label", negative_label ? Field::INT32 : Field::UINT32);
  blob.row_step = blob.point_step * blob.width;
  blob.data.resize(static_cast<std::size_t>(blob.point_step) * cloud.size());

  for (std::size_t i = 0; i < cloud.size(); ++i) {
    std::uint8_t* p = blob.data.data() + i * blob.point_step;
    std::size_t f = 0;
    for (int a = 0; a < 3; ++a) store(p + blob.fields[f++].offset, cloud.points[i][a]);
    if (cloud.has_normals()) {
      for (int a = 0; a < 3; ++a) store(p + blob.fields[f++].offset, cloud.normals[i][a]);
    }
    if (cloud.has_colors()) {
      store(p + blob.fields[f++].offset, pack_point_color(cloud.colors[i]));
    }
    if (cloud.has_labels()) store(p + blob.fields[f++].offset, cloud.labels[i]);
  }
  out.origin << cloud.T_cloud_sensor.translation().cast<float>(), 0.0f;
  out.orientation = Eigen::Quaternionf(cloud.T_cloud_sensor.linear().cast<float>()).normalized();
  return out;
}

void sensor_from_pcl(const Eigen::Vector4f& origin, const Eigen::Quaternionf& orientation,
                     PointCloud& cloud) {
  cloud.T_cloud_sensor = Eigen::Isometry3d::Identity();
  cloud.T_cloud_sensor.translation() = origin.head<3>().cast<double>();
  // A file may carry an unnormalised or zero quaternion; fall back to identity rather than NaN.
  const Eigen::Quaterniond q = orientation.cast<double>();
  if (q.norm() > 1e-9 && q.coeffs().allFinite()) {
    cloud.T_cloud_sensor.linear() = q.normalized().toRotationMatrix();
  }
}

}  // namespace lmk::detail
