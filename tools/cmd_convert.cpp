// SPDX-License-Identifier: BSD-3-Clause
// lmk convert IN OUT [--encoding E]: between PCD, PLY and XYZ, keeping what the target can hold.

#include <cstdio>
#include <map>
#include <memory>

#include "lmk/geometry/cloud_io.h"
#include "tools/cli_common.h"

namespace lmk::cli {
namespace {

struct ConvertOptions {
  std::string input, output;
  Encoding encoding = Encoding::kBinaryCompressed;
};

int run_convert(const ConvertOptions& options) {
  format_from_path(options.output);  // reject an unknown output extension before reading
  const PointCloud cloud = read_cloud(options.input);
  write_cloud(options.output, cloud, {options.encoding});
  const CloudFormat format = format_from_path(options.output);
  const Encoding written = format == CloudFormat::kXyz ? Encoding::kAscii
                           : format == CloudFormat::kPly && options.encoding != Encoding::kAscii
                               ? Encoding::kBinary
                               : options.encoding;
  std::printf("wrote %s: %zu points (%s %s)\n", options.output.c_str(), cloud.size(),
              to_string(format), to_string(written));
  return kOk;
}

}  // namespace

Subcommand add_convert(CLI::App& app) {
  auto options = std::make_shared<ConvertOptions>();
  CLI::App* sub =
      app.add_subcommand("convert", "Convert a point cloud between .pcd, .ply and .xyz");
  sub->add_option("input", options->input, "Point-cloud file to read")->required();
  sub->add_option("output", options->output, "File to write; its extension chooses the format")
      ->required();
  const std::map<std::string, Encoding> encodings = {
      {"ascii", Encoding::kAscii},
      {"binary", Encoding::kBinary},
      {"binary_compressed", Encoding::kBinaryCompressed}};
  sub->add_option("--encoding", options->encoding,
                  "ascii, binary or binary_compressed (PCD default; PLY uses binary)")
      ->transform(CLI::CheckedTransformer(encodings, CLI::ignore_case));
  return {sub, [options] { return run_convert(*options); }};
}

}  // namespace lmk::cli
