#pragma once
// Per-format readers and writers behind cloud_io.h. Internal: not installed.
// Readers get the whole file in memory and the path for messages; they throw lmk::Error.

#include <filesystem>
#include <string>

#include "geometry/cloud_io.h"

namespace lmk::detail {

CloudFile read_pcd(const std::string& path, const std::string& bytes);
CloudFile read_ply(const std::string& path, const std::string& bytes);
CloudFile read_xyz(const std::string& path, const std::string& bytes);

void write_pcd(const std::filesystem::path& file, const PointCloud& cloud, Encoding encoding);
void write_ply(const std::filesystem::path& file, const PointCloud& cloud, Encoding encoding);
void write_xyz(const std::filesystem::path& file, const PointCloud& cloud);

}  // namespace lmk::detail
