#include "tools/cli_common.h"

#include <cmath>

#include "geometry/error.h"
#include "geometry/pose.h"

namespace lmk::cli {

Eigen::Vector3d rpy_degrees(const Eigen::Matrix3d& R) {
  Eigen::Vector3d rpy = rpy_from_rotation(R) * 180.0 / M_PI;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(rpy[i]) < 0.005) rpy[i] = 0.0;
  }
  return rpy;
}

std::optional<Eigen::Vector3d> UpOptions::vector() const {
  if (up.empty()) return std::nullopt;
  const Eigen::Vector3d v(up[0], up[1], up[2]);
  if (!v.allFinite() || v.norm() < 1e-9) throw Error("--up must be a finite non-zero vector");
  return v;
}

void add_up_options(CLI::App* sub, UpOptions& options) {
  sub->add_option("--up", options.up,
                  "Up axis in the scene frame (default: the sensor's -y, or +z with --base-frame)")
      ->expected(3);
  sub->add_flag("--base-frame", options.base_frame,
                "The scene is expressed in a robot base frame, whose +z is up");
}

void add_search_options(CLI::App* sub, FindSettings& s) {
  sub->add_option("--method", s.method, "Search method: fast or reference")
      ->check(CLI::IsMember(search_methods()))
      ->capture_default_str();
  sub->add_option("--metric", s.metric,
                  "Error metric: paper, rapid, vdb or visibility (default: visibility for fast, "
                  "paper for reference)");
  sub->add_option("--threshold", s.threshold,
                  "Largest error of a match, m (default: the metric's own)");
  sub->add_option("--orientations", s.orientations,
                  "Fast: 'upright' (any yaw, tilt up to --max-tilt) or 'full' (all of SO(3))")
      ->check(CLI::IsMember({"upright", "full"}))
      ->capture_default_str();
  sub->add_option_function<double>(
      "--max-tilt", [&s](double degrees) { s.max_tilt = degrees * M_PI / 180.0; },
      "Fast, upright: largest tilt of the landmark's up axis, degrees (default 60)");
  sub->add_option("--min-coverage", s.min_coverage,
                  "Fast: least fraction of landmark points with scene support")
      ->capture_default_str();
  sub->add_option("--max-empty-violation", s.max_empty_space_violation,
                  "Fast: largest fraction of the landmark's empty space the scene may occupy")
      ->capture_default_str();
  sub->add_option_function<std::size_t>(
      "--max-seeds", [&s](const std::size_t& n) { s.max_seeds = n; },
      "Most seeds (below this: fast, --seeds-per-instance; reference, 5% of the points); default "
      "1000 for the reference, as the paper, and 2000 for fast");
  sub->add_option("--seeds-per-instance", s.seeds_per_instance,
                  "Fast: seeds expected on one instance of the landmark")
      ->capture_default_str();
  sub->add_option("--seed", s.seed, "Random seed of the seed sampling")->capture_default_str();
}

}  // namespace lmk::cli
