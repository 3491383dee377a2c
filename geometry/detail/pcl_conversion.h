// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// PointCloud <-> pcl::PCLPointCloud2, the field-generic blob that PCL's PCD and PLY readers and
// writers speak. Internal: not installed, so that lmk's public headers never include PCL.

#include <pcl/PCLPointCloud2.h>

#include <string>
#include <vector>

#include "lmk/geometry/point_cloud.h"

namespace lmk::detail {

/// Throws lmk::Error, naming `path` and the fields present, unless the blob has x, y and z.
void require_xyz(const pcl::PCLPointCloud2& blob, const std::string& path);

/// Reads x/y/z (any numeric type), normal_x/y/z, rgb or rgba (float-packed or integer) and label;
/// ignores every other field. Throws lmk::Error, naming `path`, when x, y or z is missing.
PointCloud from_pcl(const pcl::PCLPointCloud2& blob, const std::string& path);

/// The blob's field names in order, without padding fields ("_").
std::vector<std::string> field_names(const pcl::PCLPointCloud2& blob);

/// What PCL's writers take: the field blob and the sensor pose as (origin, orientation).
struct PclCloud {
  pcl::PCLPointCloud2 blob;
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
};

/// Float xyz, float normals, colour as PCL's float-packed "rgb" (or uint32 "rgba" when any alpha
/// is not 255) and "label" (uint32, or int32 when a label is negative), with the sensor pose.
PclCloud to_pcl(const PointCloud& cloud);

/// Sets cloud.T_cloud_sensor from PCL's (origin, orientation).
void sensor_from_pcl(const Eigen::Vector4f& origin, const Eigen::Quaternionf& orientation,
                     PointCloud& cloud);

}  // namespace lmk::detail
