// SPDX-License-Identifier: BSD-3-Clause
// lmk serve [SCENE...] [--landmarks DIR] [--programs DIR] [--port 8080] [--bind 127.0.0.1]: the
// local web interface (docs/serve.md): see scenes, capture landmarks with a box, find them, and
// look at PbD programs' plans, in the browser.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <thread>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/search/scene_footprint.h"
#include "lmk/serve/access_guard.h"
#include "lmk/serve/http_server.h"
#include "lmk/serve/memory_budget.h"
#include "tools/cli_common.h"
#include "tools/interrupt.h"

namespace lmk::cli {
namespace {

struct ServeOptions {
  serve::ServeSettings settings;
  UpOptions up;
  double max_upload_mib = 256.0;
  double max_json_mib = 8.0;
  double memory_budget_gb = 0.0;  // 0: half the machine's memory
  bool quiet = false;
};

// How long Ctrl-C waits for the jobs under way to end at their next progress report, s.
constexpr double kStopGrace = 1.0;

int run_serve(ServeOptions& o) {
  serve::ServeSettings& s = o.settings;
  for (const std::string& scene : s.scenes) format_from_path(scene);  // before anything is read
  s.base_frame = o.up.base_frame;
  s.up = o.up.vector();
  s.max_upload_bytes = static_cast<std::size_t>(o.max_upload_mib * 1024.0 * 1024.0);
  s.max_json_bytes = static_cast<std::size_t>(o.max_json_mib * 1024.0 * 1024.0);
  s.memory_budget = o.memory_budget_gb > 0.0 ? static_cast<std::size_t>(o.memory_budget_gb * 1e9)
                                             : serve::default_memory_budget();
  if (s.token.empty() && !s.no_token) {
    if (const char* token = std::getenv("LMK_SERVE_TOKEN"); token != nullptr) s.token = token;
  }
  if (s.no_token && serve::is_loopback_name(s.bind)) {
    std::fprintf(stderr,
                 "warning: --no-token: any program of this machine, and any web page open in its "
                 "browser that guesses the port, can write landmarks into %s\n",
                 s.landmarks_dir.c_str());
  } else if (!s.no_token && !serve::is_loopback_name(s.bind)) {
    std::fprintf(stderr,
                 "warning: --bind %s: whoever has the token can see your scenes and write "
                 "landmarks into %s, and it crosses the network unencrypted (plain HTTP)\n",
                 s.bind.c_str(), s.landmarks_dir.c_str());
  }
  if (!s.scenes.empty()) {
    std::printf("reading %zu scene%s\n", s.scenes.size(), s.scenes.size() == 1 ? "" : "s");
    std::fflush(stdout);
  }
  serve::HttpServer server(s, o.quiet ? nullptr : &std::cerr);
  const int port = server.bind();
  const std::string host = s.bind.find(':') != std::string::npos ? "[" + s.bind + "]" : s.bind;
  std::printf("lmk serve: %zu scene%s, landmarks in %s%s; memory budget %s\n", s.scenes.size(),
              s.scenes.size() == 1 ? "" : "s", s.landmarks_dir.c_str(),
              s.programs_dir.empty() ? "" : (", programs in " + s.programs_dir).c_str(),
              describe_bytes(s.memory_budget).c_str());
  const std::string query = server.token().empty() ? "" : "?token=" + server.token();
  std::printf("open http://%s:%d/%s (Ctrl-C stops)\n", host.c_str(), port, query.c_str());
  std::fflush(stdout);

  // Ctrl-C stops the server; the searches under way are dropped, nothing is half-written (the
  // landmark files are written atomically).
  StopOnSigint sigint;
  std::thread watcher([&server] {
    while (!StopOnSigint::requested()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    server.stop();
  });
  server.run();
  if (!StopOnSigint::requested()) {
    watcher.detach();  // run() ended on its own: the watcher ends with the process
    throw Error("the server stopped unexpectedly");
  }
  watcher.join();
  // A search stops at its next seed; a stage without progress reports (indexing a scene of
  // millions of points) would hold the exit for seconds. Ctrl-C stops within 2 s regardless: the
  // process leaves such a job behind, and nothing is half-written (landmarks are written
  // atomically; the next start removes the scratch directory).
  if (!server.jobs_ended_within(kStopGrace)) {
    std::printf("lmk serve: stopped (a job under way was left unfinished)\n");
    std::fflush(stdout);
    std::fflush(stderr);
    std::_Exit(kOk);
  }
  std::printf("lmk serve: stopped\n");
  return kOk;
}

}  // namespace

Subcommand add_serve(CLI::App& app) {
  auto o = std::make_shared<ServeOptions>();
  serve::ServeSettings& s = o->settings;
  CLI::App* sub = app.add_subcommand(
      "serve",
      "Web interface: view scenes, capture landmarks with a box, find them, plan programs");
  sub->add_option("scenes", s.scenes, "Scene clouds to offer (.pcd, .ply, .xyz)")
      ->check(CLI::ExistingFile);
  sub->add_option("--landmarks", s.landmarks_dir,
                  "Directory of landmarks (NAME.lmk): listed, searched, and written by captures; "
                  "created if missing")
      ->capture_default_str();
  add_depth_correction_option(sub, s.depth_correction);
  sub->add_option("--calibration,--confidence-calibration", s.confidence_calibration,
                  "Confidence calibration file (lmk calibrate-confidence) every search uses; "
                  "default: lmk's built-in one")
      ->check(CLI::ExistingFile);
  sub->add_option("--programs", s.programs_dir, "Directory of PbD programs (.json) to plan")
      ->check(CLI::ExistingDirectory);
  sub->add_option("--port", s.port, "TCP port; 0 picks a free one")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  sub->add_option("--bind", s.bind,
                  "Address to listen on; only this machine by default (another address warns)")
      ->capture_default_str();
  sub->add_option("--token", s.token,
                  "Token every request must carry (default: $LMK_SERVE_TOKEN, else a random one, "
                  "printed in the address)");
  sub->add_flag("--no-token", s.no_token,
                "Ask no token (loopback only; any local program or web page could then drive "
                "the server)")
      ->excludes("--token");
  sub->add_option("--allow-host", s.allowed_hosts,
                  "Further host name the server may be reached by (repeatable; loopback names and "
                  "the --bind address always are)");
  sub->add_option("--workers", s.workers, "Searches run at once; more wait in a queue")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  sub->add_option("--max-upload", o->max_upload_mib, "Largest uploaded cloud, MiB")
      ->check(within(0.001, 4096.0))
      ->capture_default_str();
  sub->add_option("--max-json", o->max_json_mib,
                  "Largest JSON request body, MiB; its parse is reserved in the memory budget "
                  "before it is read")
      ->check(within(0.001, 256.0))
      ->capture_default_str();
  sub->add_option("--memory-budget", o->memory_budget_gb,
                  "Memory the uploads, scenes and jobs may take at once, GB: each is priced before "
                  "it starts and refused (503, Retry-After) when it does not fit (default: half "
                  "the machine's memory)")
      ->check(within(0.1, 1024.0));
  sub->add_option("--torso", s.torso, "Simulated PR2 torso height for program plans, m")
      ->check(within(0.0, 0.33))
      ->capture_default_str();
  sub->add_option("--three", s.three_dir,
                  "three.js directory (default: Debian libjs-three's /usr/share/javascript/three)");
  add_up_options(sub, o->up);
  sub->add_flag("--quiet", o->quiet, "Do not log requests");
  return {sub, [o] { return run_serve(*o); }};
}

}  // namespace lmk::cli
