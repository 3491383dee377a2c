// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// PointCloud: the point set every lmk module works on.
//
// Points are float xyz (what depth sensors deliver; 12 bytes a point). An organised cloud keeps the
// sensor's width x height grid, row-major, with NaN points where the sensor had no return; an
// unorganised cloud has height 1. Normals, colours and labels are optional: each attribute vector
// is either empty or exactly as long as `points`.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace lmk {

using Index = std::uint32_t;
using Indices = std::vector<Index>;

struct Color {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
  bool operator==(const Color& o) const { return r == o.r && g == o.g && b == o.b && a == o.a; }
};

class PointCloud {
 public:
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;  ///< empty, or unit normals (NaN where undefined)
  std::vector<Color> colors;             ///< empty, or one per point
  std::vector<std::int32_t> labels;      ///< empty, or one per point

  std::uint32_t width = 0;   ///< points per row; equals size() when unorganised
  std::uint32_t height = 1;  ///< rows; 1 when unorganised

  /// Pose of the sensor in the cloud's frame (T_cloud_sensor): its translation is the sensor
  /// origin, from which every point was observed. Read from and written to the PCD VIEWPOINT.
  Eigen::Isometry3d T_cloud_sensor = Eigen::Isometry3d::Identity();

  PointCloud() = default;
  /// An unorganised cloud of the given points.
  explicit PointCloud(std::vector<Eigen::Vector3f> pts);

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool is_organized() const { return height > 1; }
  bool has_normals() const { return !normals.empty(); }
  bool has_colors() const { return !colors.empty(); }
  bool has_labels() const { return !labels.empty(); }
  Eigen::Vector3d sensor_origin() const { return T_cloud_sensor.translation(); }

  /// Number of points whose three coordinates are finite.
  std::size_t count_finite() const;

  /// Axis-aligned bounds of the finite points; empty() when there are none.
  Eigen::AlignedBox3f bounds() const;

  /// Makes the cloud unorganised (height 1, width = size()).
  void set_unorganized();

  /// The points at `indices`, with their attributes, as an unorganised cloud with the same sensor.
  PointCloud select(const Indices& indices) const;

  /// The cloud moved rigidly by T_new_old (points, normals and the sensor pose; the organisation
  /// and the non-finite points are kept), as if the whole scene had been picked up and put down.
  PointCloud transformed(const Eigen::Isometry3d& T_new_old) const;

  /// Throws lmk::Error if an attribute's length differs from the number of points or the
  /// width x height grid does not hold exactly size() points. `what` names the cloud in the
  /// message.
  void validate(const std::string& what) const;
};

inline bool is_finite(const Eigen::Vector3f& p) {
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

}  // namespace lmk
