// SPDX-License-Identifier: BSD-3-Clause
// lmk landmark show FILE | export FILE OUTDIR | import DIR OUT.lmk | upgrade FILE...

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "lmk/geometry/chroma.h"
#include "lmk/geometry/pose.h"
#include "lmk/landmark/landmark_file.h"
#include "tools/cli_common.h"

namespace lmk::cli {
namespace {

struct LandmarkOptions {
  std::string file, dir, output;
  std::vector<std::string> files;
};

// What the capture check found (landmark/capture_findings.h), as the file keeps it.
void print_findings(const CaptureFindings& f) {
  if (std::isfinite(f.noise)) {
    std::printf("capture noise  %.2f mm (measured in the capture frame)\n", f.noise * 1000.0);
  } else {
    std::printf("capture noise  not measured (the sensor model's stands in)\n");
  }
  if (f.slide == 0.0) {
    std::printf("slides         none: the shape fixes its pose within the noise\n");
  } else if (std::isinf(f.slide)) {
    std::printf("slides         free %s\n", f.slide_turn ? "turn" : "slide");
  } else {
    std::printf("slides         %.1f cm (%s)\n", f.slide * 100.0, f.slide_turn ? "turn" : "slide");
  }
  std::printf("symmetry axes  %zu\n", f.symmetry_axes.size());
  if (!f.look_alike_checked) {
    std::printf("look-alikes    not checked (a file from before format 4: capture it again)\n");
  } else {
    std::printf("look-alikes    %zu%s\n", f.look_alikes,
                f.found_itself ? "" : ", and not found in its own capture scene");
  }
  for (const std::string& w : f.warnings()) std::printf("warning        %s\n", w.c_str());
}

int run_show(const LandmarkOptions& o) {
  const Landmark l = load_landmark(o.file);
  const Eigen::Vector3d c = l.box.center();
  const Eigen::Vector3d rpy = rpy_degrees(l.box.pose.linear());
  std::printf("name           %s\n", printable(l.name, kMaxPrintedPath).c_str());
  std::printf("format         lmk %d\n", landmark_file_version(o.file));
  std::printf("points         %zu\n", l.points.size());
  std::printf("box centre     %.4f %.4f %.4f m\n", c.x(), c.y(), c.z());
  std::printf("box rpy        %.2f %.2f %.2f deg\n", rpy.x(), rpy.y(), rpy.z());
  std::printf("box size       %.4f %.4f %.4f m\n", l.box.size.x(), l.box.size.y(), l.box.size.z());
  std::printf("sensor origin  %.4f %.4f %.4f\n", l.sensor_origin.x(), l.sensor_origin.y(),
              l.sensor_origin.z());
  std::printf("views          %zu\n", l.view_count());
  for (std::size_t v = 1; v < l.view_origins.size(); ++v) {  // the first is the sensor origin
    const Eigen::Vector3d& o = l.view_origins[v];
    std::printf("view %-2zu origin %.4f %.4f %.4f\n", v + 1, o.x(), o.y(), o.z());
  }
  // Colour: how many points carry a hue the colour term can compare (geometry/chroma.h).
  if (l.points.has_colors()) {
    const auto hued = std::count_if(l.points.colors.begin(), l.points.colors.end(),
                                    [](const Color& c) { return chroma_of(c).has_value(); });
    std::printf("colour         yes, %td of the points with a hue\n", hued);
  } else {
    std::printf("colour         no\n");
  }
  std::printf("leaf           %.4f m\n", l.settings.leaf_size);
  std::printf("empty space    %zu voxels observed free (the distance field is rebuilt on load)\n",
              l.empty_space.size());
  print_findings(l.findings);
  return kOk;
}

// Rewrites each file of format 1 to 4 in format 5; a file that cannot be read is named and left as
// it is, and the others go on.
int run_upgrade(const LandmarkOptions& o) {
  int status = kOk;
  for (const std::string& file : o.files) {
    try {
      const int version = upgrade_landmark_file(file);
      if (version == kLandmarkFormatVersion) {
        std::printf("%s: already format %d\n", printable(file, kMaxPrintedPath).c_str(), version);
      } else {
        std::printf("%s: format %d -> %d\n", printable(file, kMaxPrintedPath).c_str(), version,
                    kLandmarkFormatVersion);
      }
    } catch (const Error& e) {
      std::fprintf(stderr, "lmk: error: %s\n", printable(e.what(), 1000).c_str());
      status = kBadInput;
    }
  }
  return status;
}

}  // namespace

Subcommand add_landmark(CLI::App& app) {
  auto o = std::make_shared<LandmarkOptions>();
  CLI::App* sub = app.add_subcommand("landmark", "Inspect, export and import landmark files");
  sub->require_subcommand(1);
  CLI::App* show =
      sub->add_subcommand("show", "Name, box, points, views, colour and findings of a .lmk");
  show->add_option("file", o->file, "Landmark file (.lmk)")->required();
  CLI::App* exp = sub->add_subcommand("export", "Write OUTDIR/points.pcd and OUTDIR/landmark.json");
  exp->add_option("file", o->file, "Landmark file (.lmk)")->required();
  exp->add_option("outdir", o->dir, "Directory to write (created if needed)")->required();
  CLI::App* imp =
      sub->add_subcommand("import", "Build a .lmk from DIR/points.pcd and DIR/landmark.json");
  imp->add_option("dir", o->dir, "Directory holding points.pcd and landmark.json")->required();
  imp->add_option("output", o->output, "Landmark file to write (.lmk)")
      ->required()
      ->check(output_extension(".lmk", "a landmark file"));
  CLI::App* upgrade = sub->add_subcommand(
      "upgrade", "Rewrite .lmk files of formats 1 to 4 (OpenVDB) in format 5, in place");
  upgrade->add_option("files", o->files, "Landmark files (.lmk)")->required();
  return {sub, [o, show, exp, imp, upgrade] {
            if (show->parsed()) return run_show(*o);
            if (upgrade->parsed()) return run_upgrade(*o);
            if (exp->parsed()) {
              export_landmark(load_landmark(o->file), o->dir);
              std::printf("wrote %s/points.pcd and %s/landmark.json\n", o->dir.c_str(),
                          o->dir.c_str());
              return static_cast<int>(kOk);
            }
            (void)imp;
            const Landmark l = import_landmark(o->dir);
            save_landmark(o->output, l);
            std::printf("wrote %s: landmark '%s', %zu points\n", o->output.c_str(), l.name.c_str(),
                        l.points.size());
            return static_cast<int>(kOk);
          }};
}

}  // namespace lmk::cli
