// SPDX-License-Identifier: BSD-3-Clause
// lmk calibrate-depth SEQUENCE -o FILE.json [--cells C R] [--gap MIN MAX] [--every N]: fit a depth
// camera's fixed depth error from a sequence of its frames with camera poses (eval/
// depth_calibration.h), and write the correction that capture and search then apply to that
// camera's frames (--depth-correction; landmark/depth_correction_file.h).

#include <algorithm>
#include <cstdio>
#include <memory>
#include <numeric>

#include "lmk/datasets/depth_calibration.h"
#include "lmk/datasets/rgbd_sequence.h"
#include "lmk/geometry/error.h"
#include "lmk/landmark/depth_correction_file.h"
#include "tools/cli_common.h"
#include "tools/progress.h"

namespace lmk::cli {
namespace {

struct CalibrateDepthOptions {
  std::string sequence, output;
  std::vector<double> intrinsics;  ///< fx fy cx cy
  std::vector<int> cells;          ///< cols rows
  std::vector<std::size_t> gap;    ///< min max, in frames used
  std::size_t every = 1;
  DepthCalibrationSettings settings;
};

int run_calibrate_depth(CalibrateDepthOptions& o) {
  RgbdReadOptions read;
  if (!o.intrinsics.empty()) read.intrinsics = intrinsics_of_option(o.intrinsics);
  if (!o.cells.empty()) {
    o.settings.cols = o.cells[0];
    o.settings.rows = o.cells[1];
  }
  if (!o.gap.empty()) {
    if (o.gap[0] > o.gap[1]) throw Error("calibrate-depth: --gap MIN MAX needs MIN <= MAX");
    o.settings.min_gap = o.gap[0];
    o.settings.max_gap = o.gap[1];
  }
  const RgbdSequence sequence = read_rgbd_sequence(o.sequence, read);
  std::vector<PointCloud> clouds;
  std::vector<Eigen::Isometry3d> poses;
  {
    ProgressBar bar("calibrate-depth: reading frames");
    for (std::size_t i = 0; i < sequence.frames.size(); i += o.every) {
      clouds.push_back(load_rgbd_frame(sequence.frames[i]));
      poses.push_back(sequence.frames[i].T_world_camera);
      bar.update(i + 1, sequence.frames.size());
    }
  }
  std::vector<const PointCloud*> views;
  for (const PointCloud& c : clouds) views.push_back(&c);
  DepthCalibration fit =
      fit_depth_correction(views, poses, sequence.frames.front().intrinsics, o.settings);
  fit.source = o.sequence + " (" + sequence.layout + " layout, " + std::to_string(clouds.size()) +
               " frames)";
  save_depth_correction(o.output, fit);
  const std::vector<double>& d = fit.correction.per_metre;
  const double mean = std::accumulate(d.begin(), d.end(), 0.0) / static_cast<double>(d.size());
  const auto [lo, hi] = std::minmax_element(d.begin(), d.end());
  std::printf(
      "wrote %s: %d x %d cells fitted on %zu frames, %zu correspondences, their disagreement "
      "%.1f mm -> %.1f mm RMS; D %.1f mm/m^2 on average (%.1f to %.1f): a depth of 2 m corrected "
      "by %.1f mm\n",
      o.output.c_str(), fit.correction.cols, fit.correction.rows, clouds.size(),
      fit.correspondences, 1000.0 * fit.rms_before, 1000.0 * fit.rms_after, 1000.0 * mean,
      1000.0 * *lo, 1000.0 * *hi, 4000.0 * mean);
  return kOk;
}

}  // namespace

Subcommand add_calibrate_depth(CLI::App& app) {
  auto o = std::make_shared<CalibrateDepthOptions>();
  CLI::App* sub = app.add_subcommand(
      "calibrate-depth",
      "Fit a depth camera's depth error from a sequence of its frames with camera poses, for "
      "--depth-correction");
  sub->add_option("sequence", o->sequence,
                  "RGB-D sequence directory (the layouts of lmk gen --from-rgbd)")
      ->required()
      ->check(CLI::ExistingDirectory);
  sub->add_option("-o,--output", o->output, "Depth-correction file to write (.json)")
      ->required()
      ->check(output_extension(".json", "a depth-correction file"));
  sub->add_option("--intrinsics", o->intrinsics,
                  "fx fy cx cy in pixels (default: the sequence's intrinsics file)")
      ->expected(4)
      ->check(within(0.0, 1e5, true));  // pixels: no depth camera is 100,000 across
  sub->add_option("--cells", o->cells, "C R: cells across and down the image (default 8 6)")
      ->expected(2)
      ->check(CLI::Range(1, 64));
  sub->add_option("--gap", o->gap,
                  "MIN MAX: pair the frames used that lie this many apart (default 5 20)")
      ->expected(2)
      ->check(CLI::Range(std::size_t{1}, std::size_t{1000}));
  sub->add_option("--every", o->every, "Use every N-th frame of the sequence")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1000}))
      ->capture_default_str();
  sub->add_option("--pixel-step", o->settings.pixel_step, "Sample every N-th pixel across and down")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  return {sub, [o] { return run_calibrate_depth(*o); }};
}

}  // namespace lmk::cli
