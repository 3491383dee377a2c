// SPDX-License-Identifier: BSD-3-Clause
// lmk convert IN OUT [--encoding E]: between PCD, PLY and XYZ, keeping what the target can hold;
// and from a depth image (.png, .pgm) with its intrinsics to an organised cloud, coloured when a
// registered colour image is given.

#include <cstdio>
#include <map>
#include <memory>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/depth_image.h"
#include "lmk/geometry/error.h"
#include "lmk/landmark/depth_correction_file.h"
#include "tools/cli_common.h"

namespace lmk::cli {
namespace {

struct ConvertOptions {
  std::string input, output;
  Encoding encoding = Encoding::kBinaryCompressed;
  std::vector<double> intrinsics;  ///< fx fy cx cy, or one intrinsics file
  std::string intrinsics_file;
  double depth_unit = 0.001;
  std::string colour;
  std::string depth_correction;
};

// A depth image and its intrinsics to an organised cloud in the camera's optical frame.
PointCloud cloud_of_depth_image(const ConvertOptions& options) {
  PinholeIntrinsics k;
  if (!options.intrinsics_file.empty()) {
    k = read_intrinsics(options.intrinsics_file);
  } else if (options.intrinsics.size() == 4) {
    k = intrinsics_of_option(options.intrinsics);
    k.validate("--intrinsics");
  } else {
    throw Error(
        "a depth image needs its intrinsics: --intrinsics FX FY CX CY or --intrinsics-file");
  }
  DepthToCloud conversion;
  conversion.metres_per_unit = options.depth_unit;
  const DepthImage depth = read_depth_image(options.input);
  if (options.colour.empty()) return depth_to_cloud(depth, k, conversion);
  const ColourImage colour = read_colour_image(options.colour);
  return depth_to_cloud(depth, k, conversion, &colour);
}

int run_convert(const ConvertOptions& options) {
  format_from_path(options.output);  // reject an unknown output extension before reading
  const bool from_depth = is_depth_image_file(options.input);
  if (!from_depth && (!options.intrinsics.empty() || !options.intrinsics_file.empty() ||
                      !options.colour.empty())) {
    throw Error("--intrinsics, --intrinsics-file and --colour are for a depth image (.png, .pgm)");
  }
  PointCloud cloud = from_depth ? cloud_of_depth_image(options) : read_cloud(options.input);
  correct_depth(cloud, options.depth_correction);
  write_cloud(options.output, cloud, {options.encoding});
  const CloudFormat format = format_from_path(options.output);
  const Encoding written = format == CloudFormat::kXyz ? Encoding::kAscii
                           : format == CloudFormat::kPly && options.encoding != Encoding::kAscii
                               ? Encoding::kBinary
                               : options.encoding;
  std::printf("wrote %s: %zu points%s (%s %s)\n", options.output.c_str(), cloud.size(),
              from_depth ? (", " + std::to_string(cloud.count_finite()) + " with a return" +
                            (cloud.has_colors() ? ", coloured" : ""))
                               .c_str()
                         : "",
              to_string(format), to_string(written));
  return kOk;
}

}  // namespace

Subcommand add_convert(CLI::App& app) {
  auto options = std::make_shared<ConvertOptions>();
  CLI::App* sub =
      app.add_subcommand("convert",
                         "Convert a point cloud between .pcd, .ply and .xyz, or a depth image "
                         "(.png, .pgm) to an organised cloud");
  sub->add_option("input", options->input,
                  "Point-cloud file to read, or a 16-bit depth image (.png, .pgm)")
      ->required();
  sub->add_option("output", options->output, "File to write; its extension chooses the format")
      ->required();
  const std::map<std::string, Encoding> encodings = {
      {"ascii", Encoding::kAscii},
      {"binary", Encoding::kBinary},
      {"binary_compressed", Encoding::kBinaryCompressed}};
  sub->add_option("--encoding", options->encoding,
                  "ascii, binary or binary_compressed (PCD default; PLY uses binary)")
      ->transform(CLI::CheckedTransformer(encodings, CLI::ignore_case));
  sub->add_option("--intrinsics", options->intrinsics,
                  "Depth image: the pinhole intrinsics FX FY CX CY, pixels")
      ->expected(4);
  sub->add_option("--intrinsics-file", options->intrinsics_file,
                  "Depth image: the intrinsics as a 3 x 3 camera matrix or FX FY CX CY in a file")
      ->excludes("--intrinsics");
  sub->add_option("--depth-unit", options->depth_unit,
                  "Depth image: metres per depth unit (0.001: millimetres; TUM RGB-D 0.0002)")
      ->check(within(0.0, 1.0, true))  // a metre per unit is no depth image
      ->capture_default_str();
  sub->add_option("--colour,--color", options->colour,
                  "Depth image: a colour PNG registered to it, pixel for pixel");
  add_depth_correction_option(sub, options->depth_correction);
  return {sub, [options] { return run_convert(*options); }};
}

}  // namespace lmk::cli
