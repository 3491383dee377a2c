// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/detail/pcl_conversion.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <optional>

#include "lmk/geometry/error.h"

namespace lmk::detail {
namespace {

using Field = pcl::PCLPointField;

std::optional<Field> find_field(const pcl::PCLPointCloud2& blob, const std::string& name) {
  for (const Field& f : blob.fields) {
    if (f.name == name) return f;
  }
  return std::nullopt;
}

template <typename T>
T load(const std::uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

// Bytes of one value of a PCL datatype; 0 for a datatype lmk does not read.
std::size_t datatype_bytes(std::uint8_t datatype) {
  switch (datatype) {
    case Field::INT8:
    case Field::UINT8:
      return 1;
    case Field::INT16:
    case Field::UINT16:
      return 2;
    case Field::INT32:
    case Field::UINT32:
    case Field::FLOAT32:
      return 4;
    case Field::FLOAT64:
      return 8;
  }
  return 0;
}

// Every field lmk reads must lie within a point: the file readers check the header against PCL's
// way of reading it, and this is the last guard of the memory it reads (a fuzzed PCD header had
// PCL lay out 1-byte fields that were then read as floats, past the end of the data).
void require_within_point(const pcl::PCLPointCloud2& blob, const std::optional<Field>& field,
                          const std::string& path) {
  if (!field) return;
  const std::size_t bytes = datatype_bytes(field->datatype);
  if (bytes == 0) {
    throw Error(path + ": field '" + printable(field->name) + "' has a type lmk does not read");
  }
  if (field->offset + bytes > blob.point_step) {
    throw Error(path + ": field '" + printable(field->name) + "' does not fit in its point (" +
                std::to_string(blob.point_step) + " bytes)");
  }
}

double load_scalar(const std::uint8_t* p, std::uint8_t datatype) {
  switch (datatype) {
    case Field::INT8:
      return load<std::int8_t>(p);
    case Field::UINT8:
      return load<std::uint8_t>(p);
    case Field::INT16:
      return load<std::int16_t>(p);
    case Field::UINT16:
      return load<std::uint16_t>(p);
    case Field::INT32:
      return load<std::int32_t>(p);
    case Field::UINT32:
      return load<std::uint32_t>(p);
    case Field::FLOAT32:
      return load<float>(p);
    case Field::FLOAT64:
      return load<double>(p);
  }
  return std::nan("");
}

// PCL packs colour as 0xAARRGGBB in 32 bits, stored either as a float's bit pattern or an integer.
Color unpack_color(std::uint32_t packed, bool has_alpha) {
  return {static_cast<std::uint8_t>((packed >> 16) & 0xff),
          static_cast<std::uint8_t>((packed >> 8) & 0xff), static_cast<std::uint8_t>(packed & 0xff),
          has_alpha ? static_cast<std::uint8_t>(packed >> 24) : std::uint8_t{255}};
}

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

void require_xyz(const pcl::PCLPointCloud2& blob, const std::string& path) {
  if (find_field(blob, "x") && find_field(blob, "y") && find_field(blob, "z")) return;
  std::string names;
  for (const std::string& n : field_names(blob)) names += (names.empty() ? "" : " ") + n;
  throw Error(path + ": no x/y/z fields (the file has: " + (names.empty() ? "none" : names) + ")");
}

// A file's number as a whole number of type T: NaN gives 0 and values beyond T's range its
// limits. A plain cast of either is undefined behaviour (UBSan caught a NaN "rgb" double).
template <typename T>
T whole_number(double value) {
  if (!(value == value)) return T{0};
  const double low = static_cast<double>(std::numeric_limits<T>::lowest());
  const double high = static_cast<double>(std::numeric_limits<T>::max());
  return static_cast<T>(std::clamp(value, low, high));
}

PointCloud from_pcl(const pcl::PCLPointCloud2& blob, const std::string& path) {
  require_xyz(blob, path);
  const auto x = find_field(blob, "x"), y = find_field(blob, "y"), z = find_field(blob, "z");
  const auto nx = find_field(blob, "normal_x"), ny = find_field(blob, "normal_y"),
             nz = find_field(blob, "normal_z");
  const bool has_normals = nx && ny && nz;
  auto color = find_field(blob, "rgba");
  const bool has_alpha = color.has_value();
  if (!color) color = find_field(blob, "rgb");
  const auto label = find_field(blob, "label");

  for (const auto& field : {x, y, z, color, label}) require_within_point(blob, field, path);
  if (has_normals) {
    for (const auto& field : {nx, ny, nz}) require_within_point(blob, field, path);
  }
  const std::size_t n = static_cast<std::size_t>(blob.width) * blob.height;
  if (blob.data.size() < n * blob.point_step) {
    throw Error(path + ": data holds fewer bytes than width x height points need");
  }
  const std::size_t row_step =
      blob.row_step != 0 ? blob.row_step : static_cast<std::size_t>(blob.width) * blob.point_step;
  // The rows must lie within the data too: a PLY camera element sets the organisation, and a
  // damaged one gave a height of billions over a width of 0 (a loop of billions of empty rows).
  if (n > 0 &&
      (blob.height - 1) * row_step + std::size_t{blob.width} * blob.point_step > blob.data.size()) {
    throw Error(path + ": data holds fewer bytes than its rows of points need");
  }
  PointCloud cloud;
  cloud.points.resize(n);
  if (has_normals) cloud.normals.resize(n);
  if (color) cloud.colors.resize(n);
  if (label) cloud.labels.resize(n);
  for (std::size_t r = 0; n > 0 && r < blob.height; ++r) {
    for (std::size_t c = 0; c < blob.width; ++c) {
      const std::size_t i = r * blob.width + c;
      const std::uint8_t* p = blob.data.data() + r * row_step + c * blob.point_step;
      cloud.points[i] = Eigen::Vector3d(load_scalar(p + x->offset, x->datatype),
                                        load_scalar(p + y->offset, y->datatype),
                                        load_scalar(p + z->offset, z->datatype))
                            .cast<float>();
      if (has_normals) {
        cloud.normals[i] = Eigen::Vector3d(load_scalar(p + nx->offset, nx->datatype),
                                           load_scalar(p + ny->offset, ny->datatype),
                                           load_scalar(p + nz->offset, nz->datatype))
                               .cast<float>();
      }
      if (color) {
        // A float "rgb" is a bit pattern, not a number: reinterpret it, never convert it.
        const std::uint32_t packed =
            (color->datatype == Field::FLOAT32 || color->datatype == Field::UINT32 ||
             color->datatype == Field::INT32)
                ? load<std::uint32_t>(p + color->offset)
                : whole_number<std::uint32_t>(load_scalar(p + color->offset, color->datatype));
        cloud.colors[i] = unpack_color(packed, has_alpha);
      }
      if (label) {
        cloud.labels[i] =
            whole_number<std::int32_t>(load_scalar(p + label->offset, label->datatype));
      }
    }
  }
  cloud.width = blob.width;
  cloud.height = blob.height;
  return cloud;
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
      const Color& c = cloud.colors[i];
      const std::uint32_t packed = (std::uint32_t{c.a} << 24) | (std::uint32_t{c.r} << 16) |
                                   (std::uint32_t{c.g} << 8) | std::uint32_t{c.b};
      store(p + blob.fields[f++].offset, packed);
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
