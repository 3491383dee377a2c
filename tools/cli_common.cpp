// SPDX-License-Identifier: BSD-3-Clause
#include "tools/cli_common.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/geometry/settings_schema.h"
#include "lmk/geometry/worker_threads.h"

namespace lmk::cli {

CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return read_finite_number(text) ? "" : "'" + text + "' is not a finite number";
      },
      "FINITE");
}

CLI::Validator within(double lo, double hi, bool lo_exclusive) {
  char range[96];
  std::snprintf(range, sizeof range, "%s%g, %g]", lo_exclusive ? "(" : "[", lo, hi);
  const std::string bounds = range;
  return CLI::Validator(
      [lo, hi, lo_exclusive, bounds](std::string& text) -> std::string {
        const std::optional<double> v = read_finite_number(text);
        if (v && (lo_exclusive ? *v > lo : *v >= lo) && *v <= hi) return "";
        return "'" + printable(text, kEchoedBytes) + "' is not a number in " + bounds;
      },
      "NUMBER in " + bounds);
}

CLI::Validator non_negative_whole() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return read_non_negative_whole(text) ? ""
                                             : "'" + text + "' is not a non-negative whole number";
      },
      "UINT");
}

CLI::Validator worker_threads() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const std::optional<std::uint64_t> n = read_non_negative_whole(text);
        if (n && *n <= static_cast<std::uint64_t>(max_worker_threads())) return "";
        return "'" + text + "' is not a thread count in [0, " +
               std::to_string(max_worker_threads()) + "] (0 uses every core; at most " +
               std::to_string(kMaxThreadsPerCore) + " per core of this machine)";
      },
      "THREADS");
}

CLI::Validator output_extension(const std::string& extension, const std::string& what) {
  return CLI::Validator(
      [extension, what](std::string& text) -> std::string {
        const bool ends_right =
            text.size() > extension.size() &&
            text.compare(text.size() - extension.size(), extension.size(), extension) == 0;
        return ends_right ? "" : "'" + text + "': " + what + " must end in " + extension;
      },
      "PATH" + extension);
}

void add_timings_flag(CLI::App* sub, bool& timings) {
  sub->add_flag("--timings", timings,
                "Keep wall-clock times in the JSON output (without them it is byte-identical for "
                "the same inputs and settings, whatever the threads or the cache)");
}

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= text.size() && !text.empty()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    out.push_back(text.substr(start, comma - start));
    start = comma + 1;
  }
  return out;
}

nlohmann::json json_output(nlohmann::json j, bool timings) {
  if (timings) return j;
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end();) {
      const std::string& key = it.key();
      if (key.rfind("seconds", 0) == 0 || key.rfind("median_seconds", 0) == 0) {
        it = j.erase(it);
      } else {
        *it = json_output(std::move(*it), false);
        ++it;
      }
    }
  } else if (j.is_array()) {
    for (auto& item : j) item = json_output(std::move(item), false);
  }
  return j;
}

Eigen::Vector3d rpy_degrees(const Eigen::Matrix3d& R) {
  Eigen::Vector3d rpy = rpy_from_rotation(R) * 180.0 / M_PI;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(rpy[i]) < 0.005) rpy[i] = 0.0;
  }
  return rpy;
}

std::filesystem::path shared_data_dir(const std::string& option) {
  if (!option.empty()) return option;
  const char* env = std::getenv("LMK_SHARED_DATA");
  return env != nullptr && *env != '\0' ? std::filesystem::path(env)
                                        : std::filesystem::path(LMK_SHARED_DATA_DIR);
}

std::optional<Eigen::Vector3d> UpOptions::vector() const {
  if (up.empty()) return std::nullopt;
  const Eigen::Vector3d v(up[0], up[1], up[2]);
  // Its length too: 1e308 1e308 0 has finite parts but no finite length to be divided by.
  if (!v.allFinite() || !std::isfinite(v.norm()) || v.norm() < 1e-9) {
    throw Error("--up must be a finite non-zero vector");
  }
  return v;
}

void add_up_options(CLI::App* sub, UpOptions& options) {
  sub->add_option("--up", options.up,
                  "Up axis in the scene frame (default: the sensor's -y, or +z with --base-frame)")
      ->expected(3);
  sub->add_flag("--base-frame", options.base_frame,
                "The scene is expressed in a robot base frame, whose +z is up");
}

PinholeIntrinsics intrinsics_of_option(const std::vector<double>& fx_fy_cx_cy) {
  PinholeIntrinsics k;
  k.fx = fx_fy_cx_cy.at(0);
  k.fy = fx_fy_cx_cy.at(1);
  k.cx = fx_fy_cx_cy.at(2);
  k.cy = fx_fy_cx_cy.at(3);
  return k;
}

void add_depth_correction_option(CLI::App* sub, std::string& file) {
  sub->add_option("--depth-correction", file,
                  "Undo the depth camera's fitted depth error (a file of lmk calibrate-depth) on "
                  "the organised frame read, before anything else; use it at capture and search "
                  "alike")
      ->check(CLI::ExistingFile);
}

}  // namespace lmk::cli
