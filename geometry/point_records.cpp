// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/point_records.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <optional>

#include "lmk/geometry/error.h"

namespace lmk {
namespace {

using Type = PointDatatype;

std::optional<RecordField> find_field(const PointRecords& r, const std::string& name) {
  for (const RecordField& f : r.fields) {
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

double load_scalar(const std::uint8_t* p, std::uint8_t datatype) {
  switch (static_cast<Type>(datatype)) {
    case Type::kInt8:
      return load<std::int8_t>(p);
    case Type::kUint8:
      return load<std::uint8_t>(p);
    case Type::kInt16:
      return load<std::int16_t>(p);
    case Type::kUint16:
      return load<std::uint16_t>(p);
    case Type::kInt32:
      return load<std::int32_t>(p);
    case Type::kUint32:
      return load<std::uint32_t>(p);
    case Type::kFloat32:
      return load<float>(p);
    case Type::kFloat64:
      return load<double>(p);
  }
  return std::nan("");
}

// A number as a whole number of type T: NaN gives 0 and values beyond T's range its limits. A
// plain cast of either is undefined behaviour (UBSan caught a NaN "rgb" double).
template <typename T>
T whole_number(double value) {
  if (!(value == value)) return T{0};
  const double low = static_cast<double>(std::numeric_limits<T>::lowest());
  const double high = static_cast<double>(std::numeric_limits<T>::max());
  return static_cast<T>(std::clamp(value, low, high));
}

// Every field read must lie within a point: the last guard of the memory read (a fuzzed PCD header
// had PCL lay out 1-byte fields that were then read as floats, past the end of the data).
void require_within_point(const PointRecords& r, const std::optional<RecordField>& field,
                          const std::string& where) {
  if (!field) return;
  const std::size_t bytes = point_datatype_bytes(field->datatype);
  if (bytes == 0) {
    throw Error(where + ": field '" + printable(field->name) +
                "' has a type lmk does not read (datatype " + std::to_string(field->datatype) +
                ")");
  }
  if (std::size_t{field->offset} + bytes > r.point_step) {
    throw Error(where + ": field '" + printable(field->name) + "' lies beyond the point step (" +
                std::to_string(r.point_step) + " bytes)");
  }
}

// The rows must lie within the data: a PLY camera element sets the organisation, and a damaged one
// gave a height of billions over a width of 0 (a loop of billions of empty rows).
void require_rows_within_data(const PointRecords& r, const std::string& where) {
  const std::uint64_t count = std::uint64_t{r.width} * r.height;
  if (count == 0) return;  // a point step of 0 fails require_within_point first
  const std::uint64_t row_bytes = std::uint64_t{r.width} * r.point_step;
  if (r.row_step < row_bytes) {
    throw Error(where + ": row_step " + std::to_string(r.row_step) +
                " is less than width x point_step (" + std::to_string(row_bytes) + ")");
  }
  const std::uint64_t needed = std::uint64_t{r.height - 1} * r.row_step + row_bytes;
  if (needed > r.bytes) {
    throw Error(where + ": holds " + std::to_string(r.bytes) + " bytes of points, but its rows " +
                "need " + std::to_string(needed));
  }
}

}  // namespace

std::size_t point_datatype_bytes(std::uint8_t datatype) {
  switch (static_cast<Type>(datatype)) {
    case Type::kInt8:
    case Type::kUint8:
      return 1;
    case Type::kInt16:
    case Type::kUint16:
      return 2;
    case Type::kInt32:
    case Type::kUint32:
    case Type::kFloat32:
      return 4;
    case Type::kFloat64:
      return 8;
  }
  return 0;
}

Color unpack_point_color(std::uint32_t packed, bool has_alpha) {
  return {static_cast<std::uint8_t>((packed >> 16) & 0xff),
          static_cast<std::uint8_t>((packed >> 8) & 0xff), static_cast<std::uint8_t>(packed & 0xff),
          has_alpha ? static_cast<std::uint8_t>(packed >> 24) : std::uint8_t{255}};
}

std::uint32_t pack_point_color(const Color& c) {
  return (std::uint32_t{c.a} << 24) | (std::uint32_t{c.r} << 16) | (std::uint32_t{c.g} << 8) |
         std::uint32_t{c.b};
}

bool is_read_field(const std::string& name) {
  static const char* const kRead[] = {"x",        "y",    "z",   "normal_x", "normal_y",
                                      "normal_z", "rgba", "rgb", "label"};
  return std::find(std::begin(kRead), std::end(kRead), name) != std::end(kRead);
}

void require_xyz_fields(const std::vector<RecordField>& fields, const std::string& where) {
  const auto has = [&fields](const char* name) {
    return std::any_of(fields.begin(), fields.end(),
                       [name](const RecordField& f) { return f.name == name; });
  };
  if (has("x") && has("y") && has("z")) return;
  std::string names;
  for (const RecordField& f : fields) {
    if (f.name != "_") names += (names.empty() ? "" : " ") + printable(f.name);  // "_": padding
  }
  throw Error(where + ": no x/y/z fields (it has: " + (names.empty() ? "none" : names) + ")");
}

PointCloud decode_point_records(const PointRecords& r, const std::string& where) {
  require_xyz_fields(r.fields, where);
  const auto x = find_field(r, "x"), y = find_field(r, "y"), z = find_field(r, "z");
  const auto nx = find_field(r, "normal_x"), ny = find_field(r, "normal_y"),
             nz = find_field(r, "normal_z");
  const bool has_normals = nx && ny && nz;
  auto color = find_field(r, "rgba");
  const bool has_alpha = color.has_value();
  if (!color) color = find_field(r, "rgb");
  const auto label = find_field(r, "label");
  for (const auto& field : {x, y, z, color, label}) require_within_point(r, field, where);
  if (has_normals) {
    for (const auto& field : {nx, ny, nz}) require_within_point(r, field, where);
  }
  require_rows_within_data(r, where);

  const std::size_t n = std::size_t{r.width} * r.height;
  PointCloud cloud;
  cloud.points.resize(n);
  if (has_normals) cloud.normals.resize(n);
  if (color) cloud.colors.resize(n);
  if (label) cloud.labels.resize(n);
  // Evaluated into a Vector3f here: an Eigen expression returned as auto would point into the
  // destroyed temporary Vector3d.
  const auto vector_at = [](const std::uint8_t* p, const RecordField& a, const RecordField& b,
                            const RecordField& c) -> Eigen::Vector3f {
    return Eigen::Vector3d(load_scalar(p + a.offset, a.datatype),
                           load_scalar(p + b.offset, b.datatype),
                           load_scalar(p + c.offset, c.datatype))
        .cast<float>();
  };
  for (std::size_t row = 0; n > 0 && row < r.height; ++row) {
    for (std::size_t col = 0; col < r.width; ++col) {
      const std::size_t i = row * r.width + col;
      const std::uint8_t* p = r.data + row * r.row_step + col * r.point_step;
      cloud.points[i] = vector_at(p, *x, *y, *z);
      if (has_normals) cloud.normals[i] = vector_at(p, *nx, *ny, *nz);
      if (color) {
        // A float "rgb" is a bit pattern, not a number: reinterpret it, never convert it.
        const bool bits = point_datatype_bytes(color->datatype) == 4;
        const std::uint32_t packed =
            bits ? load<std::uint32_t>(p + color->offset)
                 : whole_number<std::uint32_t>(load_scalar(p + color->offset, color->datatype));
        cloud.colors[i] = unpack_point_color(packed, has_alpha);
      }
      if (label) {
        cloud.labels[i] =
            whole_number<std::int32_t>(load_scalar(p + label->offset, label->datatype));
      }
    }
  }
  cloud.width = r.width;
  cloud.height = r.height;
  return cloud;
}

}  // namespace lmk
