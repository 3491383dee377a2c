// SPDX-License-Identifier: BSD-3-Clause
// lmk info FILE [--json]: what a point-cloud file holds.

#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "lmk/geometry/cloud_io.h"
#include "tools/bag_input.h"
#include "tools/cli_common.h"

namespace lmk::cli {
namespace {

struct InfoOptions {
  std::string file;
  bool json = false;
};

nlohmann::json to_json(const Eigen::Vector3f& v) { return {v.x(), v.y(), v.z()}; }
nlohmann::json to_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

int run_info(const InfoOptions& options) {
  if (is_bag(options.file)) return print_bag_info(options.file, options.json);
  const CloudFile file = read_cloud_file(options.file);
  const PointCloud& cloud = file.cloud;
  const Eigen::AlignedBox3f bounds =
      cloud.bounds();  // never empty: the reader requires a finite point
  if (options.json) {
    const nlohmann::json out = {
        {"points", cloud.size()},
        {"finite_points", cloud.count_finite()},
        {"width", cloud.width},
        {"height", cloud.height},
        {"fields", file.fields},
        {"bounds", {{"min", to_json(bounds.min())}, {"max", to_json(bounds.max())}}},
        {"sensor_origin", to_json(cloud.sensor_origin())},
    };
    std::cout << out.dump(2) << "\n";
    return kOk;
  }
  std::string fields;
  for (const std::string& f : file.fields) fields += (fields.empty() ? "" : " ") + printable(f);
  const Eigen::Vector3f lo = bounds.min(), hi = bounds.max();
  const Eigen::Vector3d o = cloud.sensor_origin();
  // The name is the user's, the fields the file's: escaped, or they could drive the terminal.
  std::printf("file           %s\n", printable(options.file, kMaxPrintedPath).c_str());
  std::printf("format         %s (%s)\n", to_string(file.format), to_string(file.encoding));
  std::printf("points         %zu (%zu finite)\n", cloud.size(), cloud.count_finite());
  if (cloud.is_organized()) {
    std::printf("organised      %u x %u\n", cloud.width, cloud.height);
  } else {
    std::printf("organised      no\n");
  }
  std::printf("fields         %s\n", fields.c_str());
  std::printf("bounds min     %.4f %.4f %.4f\n", lo.x(), lo.y(), lo.z());
  std::printf("bounds max     %.4f %.4f %.4f\n", hi.x(), hi.y(), hi.z());
  std::printf("size           %.4f %.4f %.4f\n", hi.x() - lo.x(), hi.y() - lo.y(), hi.z() - lo.z());
  std::printf("sensor origin  %.4f %.4f %.4f\n", o.x(), o.y(), o.z());
  return kOk;
}

}  // namespace

Subcommand add_info(CLI::App& app) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* sub = app.add_subcommand(
      "info", "Describe a point-cloud file (.pcd, .ply, .xyz) or a ROS bag (.bag)");
  sub->add_option("file", options->file, "Point-cloud file or ROS bag")->required();
  sub->add_flag("--json", options->json, "Print JSON instead of a table");
  return {sub, [options] { return run_info(*options); }};
}

}  // namespace lmk::cli
