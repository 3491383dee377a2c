// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What every lmk subcommand shares: exit codes and the shape of a subcommand.

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "lmk/geometry/pinhole_intrinsics.h"
#include "lmk/search/find_landmark.h"

namespace lmk {
struct TrackSettings;
}  // namespace lmk

namespace lmk::cli {

/// Exit codes: 0 success, 1 an unexpected internal failure, 2 bad input (a file, an argument).
/// 130 for a run stopped by Ctrl-C, as shells report a process ended by SIGINT.
enum ExitCode : int { kOk = 0, kInternalError = 1, kBadInput = 2, kInterrupted = 130 };

/// A subcommand: its CLI11 node (options bound to its own state) and what to run when chosen.
/// `run` may throw lmk::Error for bad input; main turns that into one line and exit code 2.
struct Subcommand {
  CLI::App* app;
  std::function<int()> run;
};

/// The shared data directory: `option` if given, else $LMK_SHARED_DATA, else ../shared/data beside
/// the source tree.
std::filesystem::path shared_data_dir(const std::string& option);

/// Roll, pitch, yaw of a rotation in degrees for printing, with values that would print as "-0.00"
/// set to 0.
Eigen::Vector3d rpy_degrees(const Eigen::Matrix3d& R);

/// Refuses a value that is not a finite number ("nan", "inf"), for values that go into
/// computations: joint values, positions, angles.
CLI::Validator finite_number();

/// Refuses a value that is not a finite number within [lo, hi] ("text" in the message), or above
/// lo when `lo_exclusive`. CLI11's Range, PositiveNumber and NonNegativeNumber let "nan" through
/// (every comparison with NaN is false): numbers of the hand-written options use this instead.
CLI::Validator within(double lo, double hi, bool lo_exclusive = false);

/// Refuses a negative whole number before CLI11 stores it in an unsigned field, where "-1" would
/// wrap around to 2^64 - 1.
CLI::Validator non_negative_whole();

/// Refuses a thread count outside [0, max_worker_threads()] (geometry/worker_threads.h), the bound
/// every --threads shares with the settings of the page and the ROS node.
CLI::Validator worker_threads();

/// Refuses an output path that does not end in `extension` (".lmk"), so that a landmark is never
/// written under a name other tools would read as a point cloud.
CLI::Validator output_extension(const std::string& extension, const std::string& what);

/// --timings: whether a command's JSON output keeps its wall-clock times. Without it the JSON is
/// byte-identical for the same inputs and settings, whatever the thread count or the cache.
void add_timings_flag(CLI::App* sub, bool& timings);

/// The JSON without its wall-clock times (every key starting "seconds" or "median_seconds"), at
/// any depth; unchanged when `timings` is set.
nlohmann::json json_output(nlohmann::json j, bool timings);

/// "a,b,c" as {"a", "b", "c"}; "" as nothing.
std::vector<std::string> split_commas(const std::string& text);

/// The scene-frame options that say which way is up: --up X Y Z and --base-frame.
struct UpOptions {
  std::vector<double> up;
  bool base_frame = false;
  /// The --up vector, if given (lmk::Error for a zero or non-finite one).
  std::optional<Eigen::Vector3d> vector() const;
};
void add_up_options(CLI::App* sub, UpOptions& options);

/// The pinhole intrinsics of an --intrinsics FX FY CX CY option (four values, as CLI11 checked).
PinholeIntrinsics intrinsics_of_option(const std::vector<double>& fx_fy_cx_cy);

/// --depth-correction FILE: the depth camera's fitted error (lmk calibrate-depth), undone on the
/// organised frame read before anything else (landmark/depth_correction_file.h's correct_depth).
void add_depth_correction_option(CLI::App* sub, std::string& file);

/// The options of a search that lmk find, eval and ablate share: one flag per search setting
/// (find_settings.h), grouped by stage in --help; the execution stage (--threads) only when
/// `with_execution`. `settings` must outlive the parse.
void add_search_options(CLI::App* sub, FindSettings& settings, bool with_execution = false);
/// One flag per field of CaptureSettings's description (--leaf-size, --min-points, ...), but the up
/// axis and the base frame, which add_up_options gives.
void add_capture_options(CLI::App* sub, CaptureSettings& settings);

/// What lmk track and lmk eval-track share: the search's options (with --threads), --follow-margin
/// and --search-margin.
void add_track_options(CLI::App* sub, TrackSettings& settings);

Subcommand add_bench(CLI::App& app);
Subcommand add_info(CLI::App& app);
Subcommand add_metrics(CLI::App& app);
Subcommand add_convert(CLI::App& app);
Subcommand add_gen(CLI::App& app);
Subcommand add_calibrate_depth(CLI::App& app);
Subcommand add_calibrate_confidence(CLI::App& app);
Subcommand add_capture(CLI::App& app);
Subcommand add_find(CLI::App& app);
Subcommand add_track(CLI::App& app);
Subcommand add_eval_track(CLI::App& app);
Subcommand add_landmark(CLI::App& app);
Subcommand add_robot(CLI::App& app);
Subcommand add_eval(CLI::App& app);
Subcommand add_ablate(CLI::App& app);
Subcommand add_pbd(CLI::App& app);
Subcommand add_sensor_check(CLI::App& app);
Subcommand add_serve(CLI::App& app);
Subcommand add_slurm(CLI::App& app);

}  // namespace lmk::cli
