// SPDX-License-Identifier: BSD-3-Clause
// lmk sensor-check [--data DIR] [--json FILE]: the simulated Kinect against the real Kinect frames
// of the shared data, per depth range: the residual spread of planes and the spacing of the depth
// levels (sim/sensor_validation.h, docs/datasets.md).

#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/error.h"
#include "lmk/sim/scene_types.h"
#include "lmk/sim/sensor_validation.h"
#include "tools/cli_common.h"
#include "tools/progress.h"

namespace lmk::cli {
namespace {

struct SensorCheckOptions {
  std::string data, json;
  double tolerance = 0.3;
  double bin = 0.25;
  std::size_t min_patches = 20;
  PlanePatchSettings patches;
  DepthSensorSettings sensor;
};

double ratio(double simulated, double real) { return simulated / real; }

int run_sensor_check(const SensorCheckOptions& o) {
  const std::string dir = shared_data_dir(o.data).string();
  const std::vector<std::string> files = sensor_validation_files(dir);
  if (files.empty())
    throw Error(dir + ": no real Kinect frames (mosd/learn/*.pcd, pcl/*.pcd); give --data DIR");
  SensorValidation validation(o.sensor, o.bin, o.patches);
  std::size_t patches = 0;
  DepthEdgeCount real_edges, simulated_edges;
  {
    const std::size_t scenes = scene_types().size();
    ProgressBar bar("sensor-check");
    for (std::size_t i = 0; i < files.size(); ++i) {
      const RealFrame frame = load_sensor_validation_frame(files[i]);
      patches += validation.add_frame(frame.cloud, frame.keep);
      real_edges.add(count_depth_edges(frame.cloud));
      bar.update(i + 1, files.size() + scenes);
    }
    simulated_edges = simulated_depth_edges(o.sensor, [&](std::size_t done, std::size_t) {
      bar.update(files.size() + done, files.size() + scenes);
    });
  }
  const std::vector<SensorRangeComparison> rows = validation.compare(o.min_patches);
  std::printf("%zu planar patches in %zu real frames; simulated twins from the same pixels\n\n",
              patches, files.size());
  std::printf("%-11s %7s | %-28s | %-36s\n", "depth (m)", "patches", "residual sd (mm) real sim x",
              "level spacing (mm) real sim model x");
  bool all_within = true;
  nlohmann::json out = nlohmann::json::array();
  for (const SensorRangeComparison& r : rows) {
    const double sd_ratio = ratio(r.simulated_residual_sd, r.real_residual_sd);
    const double gap_ratio = ratio(r.simulated_level_spacing, r.real_level_spacing);
    const bool within =
        std::abs(sd_ratio - 1.0) <= o.tolerance && std::abs(gap_ratio - 1.0) <= o.tolerance;
    all_within = all_within && within;
    std::printf("%4.2f-%4.2f   %7zu | %7.2f %7.2f %6.2f       | %7.2f %7.2f %7.2f %6.2f %s\n",
                r.min_depth, r.max_depth, r.patches, 1e3 * r.real_residual_sd,
                1e3 * r.simulated_residual_sd, sd_ratio, 1e3 * r.real_level_spacing,
                1e3 * r.simulated_level_spacing, 1e3 * r.model_level_spacing, gap_ratio,
                within ? "" : "  <- beyond the tolerance");
    out.push_back({{"min_depth_m", r.min_depth},
                   {"max_depth_m", r.max_depth},
                   {"patches", r.patches},
                   {"real_residual_sd_m", r.real_residual_sd},
                   {"simulated_residual_sd_m", r.simulated_residual_sd},
                   {"real_level_spacing_m", r.real_level_spacing},
                   {"simulated_level_spacing_m", r.simulated_level_spacing},
                   {"model_level_spacing_m", r.model_level_spacing}});
  }
  std::printf(
      "\nmixed returns at depth edges (flying pixels): real %.1f%% of %zu, simulated %.1f%% "
      "of %zu (the benchmark's 17 scenes)\n",
      100.0 * real_edges.rate(), real_edges.edges, 100.0 * simulated_edges.rate(),
      simulated_edges.edges);
  std::printf("\n%s within %.0f%% at every depth\n",
              all_within ? "simulated and real agree" : "NOT", 100.0 * o.tolerance);
  if (!o.json.empty()) write_text_atomically(o.json, out.dump(2) + "\n");
  return all_within ? kOk : kInternalError;
}

}  // namespace

Subcommand add_sensor_check(CLI::App& app) {
  auto o = std::make_shared<SensorCheckOptions>();
  CLI::App* sub = app.add_subcommand(
      "sensor-check",
      "Compare the simulated Kinect with real Kinect frames: plane residuals and depth levels per "
      "range (exit 1 when they disagree beyond the tolerance)");
  sub->add_option("--data", o->data, "Shared data directory (default $LMK_SHARED_DATA)");
  sub->add_option("--tolerance", o->tolerance, "Largest relative difference accepted")
      ->check(within(0.0, 10.0))
      ->capture_default_str();
  sub->add_option("--bin", o->bin, "Width of the depth bins, m")
      ->check(within(0.0, 10.0, true))
      ->capture_default_str();
  sub->add_option("--min-patches", o->min_patches, "Fewest patches a bin needs to be compared")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1000000}))
      ->capture_default_str();
  sub->add_option("--tile", o->patches.tile, "Patch side, pixels")
      ->check(CLI::Range(4, 200))
      ->capture_default_str();
  sub->add_option(
         "--max-curvature-r2", o->patches.max_curvature_r2,
         "Patches whose residuals a quadratic explains beyond this fraction are not planes")
      ->check(within(0.0, 1.0))
      ->capture_default_str();
  // The simulated sensor's noise, so that a user can calibrate the model on frames of their own.
  sub->add_option("--noise-a", o->sensor.noise_a,
                  "Simulated axial noise sigma(z) = a + b (z - z0)^2: a, m")
      ->capture_default_str();
  sub->add_option("--noise-b", o->sensor.noise_b, "... b, 1/m")->capture_default_str();
  sub->add_option("--noise-z0", o->sensor.noise_z0, "... z0, m")->capture_default_str();
  sub->add_option("--noise-window", o->sensor.noise_window,
                  "Simulated noise correlated over blocks of this many pixels a side (odd)")
      ->capture_default_str();
  sub->add_option("--json", o->json, "Also write the comparison as JSON to FILE");
  return {sub, [o] { return run_sensor_check(*o); }};
}

}  // namespace lmk::cli
