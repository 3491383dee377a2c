// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Helpers for lmk's tests: seeded random clouds, scratch directories and the optional real data.

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/error.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk::test {

/// `n` points uniform in the cube [-half, half]^3, from a fixed seed.
PointCloud random_cloud(std::size_t n, std::uint64_t seed, float half = 1.0f);

/// A fresh, empty directory for one test, removed when the object is destroyed.
class ScratchDir {
 public:
  ScratchDir();
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::filesystem::path path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

/// The message of the lmk::Error that `f` throws, or "" when it throws none.
template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

/// Writes `text` to `path` as is.
void write_text(const std::string& path, const std::string& text);

/// The bytes of the file at `path`, as is (empty when it cannot be read).
std::string read_bytes(const std::string& path);

/// A shell command's exit code (-1 when it did not exit) and what it wrote.
struct CommandResult {
  int exit_code = -1;
  std::string out, err;
};
/// Runs `command` through the shell, its stdout and stderr captured in files of `dir`.
CommandResult run_shell(const std::string& command, const ScratchDir& dir);

/// Data that several tests generate alike (a dataset, the demo tasks' results), made once and then
/// only read: under CTest once per run, in $LMK_TEST_RUN_DIR/NAME, which the fixture test_run_dir
/// empties as the run starts (tests/CMakeLists.txt), the first test to need it making it while the
/// others wait on a lock for it to be done; outside CTest, once per process, in a scratch
/// directory. `make` writes the data into the (empty) directory it is given. Returns the directory.
std::filesystem::path shared_run_data(
    const std::string& name, const std::function<void(const std::filesystem::path&)>& make);

/// The real data directory (../shared/data, or $LMK_SHARED_DATA), or nothing when absent.
std::optional<std::filesystem::path> shared_data_dir();

/// The /proc/PID/status line `field` ("VmRSS", "VmHWM") of process `pid` ("self": this one),
/// bytes; 0 when absent.
double process_status_bytes(const std::string& field, const std::string& pid = "self");
/// Resets this process's peak resident memory (VmHWM) to what is resident now; false where the
/// kernel or a sandbox refuses (/proc/self/clear_refs). Measures the peak of one piece of work.
bool reset_peak_memory();

/// Writes a binary_compressed PCD of `points` points whose fields are `fields` (F4 each, COUNT 1)
/// and then one field "pad" of `pad_count` F4 values, every byte zero: an LZF block of maximal
/// back references, each 3 bytes expanding to 264, as the compression bomb of issue #61 was made.
/// Returns the file's size.
std::size_t write_zero_compressed_pcd(const std::string& path, std::size_t points,
                                      const std::vector<std::string>& fields,
                                      std::size_t pad_count);

/// Skips the calling test, with a message, when the real data is absent.
#define LMK_REQUIRE_SHARED_DATA(var)                                              \
  const auto var##_opt = ::lmk::test::shared_data_dir();                          \
  if (!var##_opt) GTEST_SKIP() << "../shared/data is absent; this test needs it"; \
  const std::filesystem::path var = *var##_opt

}  // namespace lmk::test
