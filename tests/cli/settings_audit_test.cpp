// SPDX-License-Identifier: BSD-3-Clause
// Issue #47: every numeric setting of every description the CLI takes (the search's stages on
// `lmk find`, the capture's on `lmk capture`) at its minimum, its maximum, NaN, infinity and one
// past its maximum: lmk answers each with exit 0 or 2 (never a crash, never a hang), within 2 s of
// CPU and 500 MB. The list comes from the descriptions, so a new setting is audited without a test
// of its own. Each run is one child process, its CPU time and peak memory its own (wait4), so that
// the load of the tests beside it does not count.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "lmk/landmark/landmark.h"
#include "lmk/search/find_settings.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

/// One numeric flag of a description, with its range in the flag's own unit.
struct NumericFlag {
  std::string flag;
  double min = 0.0, max = 0.0;
  bool integer = false;
};

template <class T>
struct Numeric
    : std::integral_constant<bool, std::is_arithmetic<T>::value && !std::is_same<T, bool>::value> {
  static constexpr bool integer = std::is_integral<T>::value;
};
template <class T>
struct Numeric<std::optional<T>> : Numeric<T> {};

struct CollectNumericFlags {
  std::vector<NumericFlag>& out;
  template <class T>
  void operator()(const SettingInfo& info, const T&) {
    if constexpr (Numeric<T>::value) {
      out.push_back({info.flag(), info.min / info.text_scale, info.max / info.text_scale,
                     Numeric<T>::integer});
    }
  }
};

/// The values each flag is tried with, as text.
std::vector<std::string> audit_values(const NumericFlag& f) {
  const auto text = [&](double v) {
    char buffer[64];
    if (f.integer) {
      std::snprintf(buffer, sizeof buffer, "%.0f", v);
    } else {
      std::snprintf(buffer, sizeof buffer, "%.17g", v);
    }
    return std::string(buffer);
  };
  return {text(f.min), text(f.max), "nan", "inf", text(f.max + 1.0)};
}

struct ChildRun {
  int exit_code = -1;    ///< -1: killed by a signal
  double seconds = 0.0;  ///< the child's CPU time, user and system: another test's load is not its
  double wall_seconds = 0.0;
  double peak_mb = 0.0;
};

/// Runs lmk with `args`, its output to `log`.
ChildRun run_lmk(const std::vector<std::string>& args, const std::string& log) {
  std::vector<std::string> argv{LMK_BINARY};
  argv.insert(argv.end(), args.begin(), args.end());
  const auto begin = std::chrono::steady_clock::now();
  const pid_t child = ::fork();
  if (child == 0) {
    std::FILE* out = std::freopen(log.c_str(), "w", stdout);
    if (out == nullptr || ::dup2(::fileno(stdout), STDERR_FILENO) < 0) ::_exit(127);
    std::vector<char*> c_argv;
    for (std::string& a : argv) c_argv.push_back(a.data());
    c_argv.push_back(nullptr);
    ::execv(c_argv[0], c_argv.data());
    ::_exit(127);
  }
  int status = 0;
  rusage usage{};
  ::wait4(child, &status, 0, &usage);
  ChildRun r;
  const auto cpu = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + 1e-6 * t.tv_usec;
  };
  r.seconds = cpu(usage.ru_utime) + cpu(usage.ru_stime);
  // A hang shows in wall time alone: bounded too, generously, as a deadline rather than a speed.
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.peak_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // KiB on Linux
  return r;
}

class SettingsAudit : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_EQ(run_lmk({"gen", dir_.file("tab.pcd")}, dir_.file("gen.log")).exit_code, 0);
    // Where the cup is: the searches are cropped about it, so that a bound's work stays small.
    ASSERT_EQ(run_lmk({"find", dir_.file("tab.pcd"), cup_, "--json", dir_.file("cup.json")},
                      dir_.file("cup.log"))
                  .exit_code,
              0);
    std::ifstream in(dir_.file("cup.json"));
    const nlohmann::json found = nlohmann::json::parse(in);
    ASSERT_FALSE(found["matches"].empty());
    for (int i = 0; i < 3; ++i) {
      centre_.push_back(std::to_string(found["matches"][0]["position"][i].get<double>()));
    }
  }

  /// Every value of every flag through `command` (the arguments before the flag); 0 or 2 each,
  /// within the bounds of time and memory.
  void audit(const std::vector<NumericFlag>& flags, const std::vector<std::string>& command) {
    ASSERT_GT(flags.size(), 5u);
    for (const NumericFlag& f : flags) {
      for (const std::string& value : audit_values(f)) {
        std::vector<std::string> args = command;
        args.push_back(f.flag);
        args.push_back(value);
        const std::string log = dir_.file("run.log");
        const ChildRun r = run_lmk(args, log);
        const std::string what = f.flag + " " + value + ": " + test::read_bytes(log).substr(0, 300);
        EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 2) << "exit " << r.exit_code << ", " << what;
        EXPECT_LT(r.seconds, 2.0) << what;
        EXPECT_LT(r.wall_seconds, 30.0) << what;
        EXPECT_LT(r.peak_mb, 500.0) << what;
        ++runs_;
        if (r.seconds > slowest_) {
          slowest_ = r.seconds;
          slowest_run_ = f.flag + " " + value;
        }
      }
    }
  }

  test::ScratchDir dir_;
  const std::string cup_ = std::string(LMK_CLI_FIXTURES) + "/cup_v2.lmk";
  std::vector<std::string> centre_;
  std::size_t runs_ = 0;
  double slowest_ = 0.0;
  std::string slowest_run_;
};

TEST_F(SettingsAudit, EverySearchSettingAtAndBeyondItsBounds) {
  std::vector<NumericFlag> flags;
  const FindSettings find;
  for_each_settings_group(find, [&](const char*, const auto& settings) {
    std::decay_t<decltype(settings)>::describe(settings, CollectNumericFlags{flags});
  });
  std::vector<std::string> command{"find",   dir_.file("tab.pcd"),  cup_,
                                   "--json", dir_.file("out.json"), "--work-volume"};
  command.insert(command.end(), centre_.begin(), centre_.end());
  for (const char* side : {"0.3", "0.3", "0.3"}) command.push_back(side);
  audit(flags, command);
  std::printf("audit: %zu runs of lmk find, the slowest %.2f s (%s)\n", runs_, slowest_,
              slowest_run_.c_str());
}

TEST_F(SettingsAudit, EveryCaptureSettingAtAndBeyondItsBounds) {
  std::vector<NumericFlag> flags;
  const CaptureSettings capture;
  CaptureSettings::describe(capture, CollectNumericFlags{flags});
  std::vector<std::string> command{"capture", dir_.file("tab.pcd"), "--name",     "cup",
                                   "-o",      dir_.file("cup.lmk"), "--no-check", "--box-center"};
  command.insert(command.end(), centre_.begin(), centre_.end());
  for (const char* side : {"--box-size", "0.12", "0.12", "0.16"}) command.push_back(side);
  audit(flags, command);
  std::printf("audit: %zu runs of lmk capture, the slowest %.2f s (%s)\n", runs_, slowest_,
              slowest_run_.c_str());
}

}  // namespace
}  // namespace lmk
