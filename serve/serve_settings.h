// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What `lmk serve` is given: the scenes, the directories it may read and write, where it listens,
// and its limits (docs/serve.md, "Safety").
#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "lmk/serve/connection_limits.h"

namespace lmk::serve {

struct ServeSettings {
  std::vector<std::string> scenes;          ///< cloud files shown in the scene picker
  std::string landmarks_dir = "landmarks";  ///< captures are written here; created if missing
  std::string programs_dir;                 ///< PbD programs offered; empty: none
  /// The depth camera's fitted error (a file of lmk calibrate-depth), undone on every scene read
  /// or uploaded, which must then be that camera's organised frames; empty: none.
  std::string depth_correction;
  /// A confidence calibration file of `lmk calibrate-confidence` (fitted for this camera) every
  /// search's confidence uses; empty: lmk's built-in one. Read once at start, never named by a
  /// request.
  std::string confidence_calibration;
  std::string bind = "127.0.0.1";  ///< loopback only unless the user says otherwise
  /// Asked of every API request and of the page (docs/serve.md, "Access"); empty: a fresh random
  /// one (HttpServer::token()), unless no_token.
  std::string token;
  bool no_token = false;  ///< ask no token: refused unless `bind` is a loopback address
  /// Names the Host header may carry beyond loopback names and `bind` (a proxy's, a machine's).
  std::vector<std::string> allowed_hosts;
  int port = 8080;                               ///< 0: any free port
  std::string three_dir;                         ///< three.js; empty: Debian's libjs-three
  std::size_t max_upload_bytes = 256u << 20;     ///< larger uploads get 413
  std::size_t max_json_bytes = 8u << 20;         ///< larger JSON request bodies get 413
  std::size_t max_uploads = 16;                  ///< uploaded scenes kept; the oldest goes first
  std::size_t max_upload_points = 5'000'000;     ///< points of one upload; more get 413
  std::size_t max_uploaded_points = 20'000'000;  ///< points of all uploads kept; oldest go first
  int workers = 2;                               ///< searches run at once; more wait in the queue
  std::size_t max_queued_jobs = 64;              ///< beyond it, new searches get 503
  /// s: a job nobody has asked about for this long is cancelled (JobLimits::abandon_after).
  double abandon_after = 60.0;
  /// Bytes the server's uploads, scenes and jobs may take at once, each priced before it starts
  /// (serve/memory_budget.h); 0: default_memory_budget(), half the machine's memory.
  std::size_t memory_budget = 0;
  /// The scenes are in a robot base frame (+z up), as `lmk find --base-frame`; otherwise up is
  /// `up`, or the sensor's -y.
  bool base_frame = false;
  std::optional<Eigen::Vector3d> up;
  double torso = 0.0;  ///< m: the simulated PR2's torso for program plans
  /// Deadlines for a request's headers and body, and the slow connections one client may hold.
  ConnectionLimits connections;
};

}  // namespace lmk::serve
