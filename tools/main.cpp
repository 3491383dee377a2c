// SPDX-License-Identifier: BSD-3-Clause
// lmk: custom perceptual landmarks for robot programming by demonstration.
// Dispatches to one subcommand; every error becomes one line on stderr and a non-zero exit.

#include <console_bridge/console.h>
#include <pcl/console/print.h>

#include <cstdio>
#include <exception>

#include "lmk/datasets/dependencies.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/memory_reuse.h"
#include "lmk/geometry/version.h"
#include "lmk/landmark/dependencies.h"
#include "lmk/occupancy/dependencies.h"
#include "lmk/pbd/dependencies.h"
#include "lmk/pr2/dependencies.h"
#include "lmk/registration/dependencies.h"
#include "lmk/search/metrics/error_metrics.h"
#include "lmk/sim/dependencies.h"
#include "tools/cli_common.h"

namespace {

std::string version_text() {
  std::string text = std::string("lmk ") + lmk::kVersion + "\n";
  for (const auto& list : {lmk::geometry_dependencies(), lmk::occupancy_dependencies(),
                           lmk::registration_dependencies(), lmk::landmark_dependencies(),
                           lmk::datasets_dependencies(), lmk::sim_dependencies(),
                           lmk::pbd_dependencies(), lmk::pr2_dependencies()}) {
    for (const auto& d : list) {
      if (text.find("  " + d.name + " ") == std::string::npos) {
        text += "  " + d.name + " " + d.version + "\n";
      }
    }
  }
  text.pop_back();
  return text;
}

// One line for a bad input, its message made printable: a message may quote a file's bytes, and
// 1000 characters hold any path and reason.
int bad_input(const lmk::Error& e) {
  std::fprintf(stderr, "lmk: error: %s\n", lmk::printable(e.what(), 1000).c_str());
  return lmk::cli::kBadInput;
}

// Every subcommand, registered with `app`, in the order `lmk --help` lists them.
std::vector<lmk::cli::Subcommand> all_subcommands(CLI::App& app) {
  using namespace lmk::cli;
  return {add_info(app),
          add_convert(app),
          add_gen(app),
          add_capture(app),
          add_find(app),
          add_track(app),
          add_eval_track(app),
          add_landmark(app),
          add_robot(app),
          add_bench(app),
          add_eval(app),
          add_ablate(app),
          add_pbd(app),
          add_sensor_check(app),
          add_calibrate_depth(app),
          add_calibrate_confidence(app),
          add_serve(app),
          add_slurm(app),
          add_metrics(app)};
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lmk::cli;
  // Searches, evaluations and benchmarks free buffers of a few megabytes a frame: kept for the
  // next frame rather than mapped and zeroed again (geometry/memory_reuse.h).
  lmk::keep_freed_memory_for_reuse();
  // PCL and urdfdom log their own messages on stderr; lmk reports every problem itself, in one
  // line.
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);  // urdfdom's logging

  CLI::App app{"lmk: find custom perceptual landmarks in point clouds, with their 6-DoF poses.",
               "lmk"};
  app.set_version_flag("--version", version_text());
  // The search options list the metrics, so the registry loads the plugins $LMK_METRIC_PLUGINS
  // names while the commands are built: one that cannot load is a bad input too.
  try {
    lmk::error_metrics();
  } catch (const lmk::Error& e) {
    return bad_input(e);
  }
  app.require_subcommand(1);
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return std::string("lmk: error: ") + e.what() + " (see --help)\n";
  });

  const std::vector<Subcommand> subcommands = all_subcommands(app);

  // CLI11 reports an unknown first word as a missing subcommand; name it instead.
  if (argc > 1 && argv[1][0] != '-') {
    std::string known;
    bool found = false;
    for (const Subcommand& sub : subcommands) {
      found = found || sub.app->get_name() == argv[1];
      known += (known.empty() ? "" : ", ") + sub.app->get_name();
    }
    if (!found) {
      std::fprintf(stderr, "lmk: error: unknown command '%s' (commands: %s; see --help)\n", argv[1],
                   known.c_str());
      return kBadInput;
    }
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help and --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kBadInput;
  }

  try {
    for (const Subcommand& sub : subcommands) {
      if (sub.app->parsed()) return sub.run();
    }
    return kInternalError;  // unreachable: require_subcommand(1) guarantees one was parsed
  } catch (const lmk::Interrupted& e) {
    std::fprintf(stderr, "lmk: %s\n", e.what());
    return kInterrupted;
  } catch (const lmk::Error& e) {
    return bad_input(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lmk: internal error: %s\n", e.what());
    return kInternalError;
  }
}
