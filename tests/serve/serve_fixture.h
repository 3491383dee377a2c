// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A running `lmk serve` for the API tests: the HTTP server in this process on a free port, over a
// rendered tabletop (the carton, cup and ball of make_tabletop_scene(1), world frame, z up), the
// same scene moved in front of a robot at the origin, a landmark directory, and a programs
// directory. Requests go through a real HTTP client.
#include <gtest/gtest.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "lmk/search/find_settings.h"
#include "lmk/serve/http_server.h"
#include "lmk/sim/tabletop_scene.h"
#include "tests/support/test_support.h"

// After Eigen: glibc's <resolv.h>, which httplib includes, defines `_res`, a name Eigen uses.
#include <httplib.h>

namespace lmk::test {

/// A response: its status and its body parsed as JSON (null when the body is not JSON).
struct Reply {
  int status = 0;
  nlohmann::json body;
  std::string text;
};

/// A client's result as a Reply (status -1 and the reason when there was no response).
Reply reply_of(const httplib::Result& r);

class ServeTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;

  /// Starts the server with `settings` over the fixture's files (scenes, directories filled in),
  /// logging its requests to `log` unless it is null.
  void start(serve::ServeSettings settings = {}, std::ostream* log = nullptr);

  /// A client of the running server that sends its token, as the page's cookie does.
  std::unique_ptr<httplib::Client> new_client() const;

  Reply get(const std::string& path);
  Reply post(const std::string& path, const nlohmann::json& body);
  Reply post_bytes(const std::string& path, const std::string& bytes);
  Reply post_text(const std::string& path, const std::string& text);
  /// `r`, or when it is a 202 for a job still running, the job polled on `c` until it ends: its
  /// status then (200 done, the job's status when failed).
  static Reply until_finished(httplib::Client& c, Reply r);
  /// POST with "wait": true, expecting the finished job; its result.
  nlohmann::json run(const std::string& path, nlohmann::json body);

  /// The carton's box as the capture tests draw it (scripts/tabletop-demo.sh's box).
  Box carton_box() const;
  /// Captures the carton into the landmark directory through the API.
  void capture_carton();

  /// The search settings of the fixture's scenes (world frame: +z up, as --base-frame).
  static FindSettings scene_settings();

  ScratchDir dir;
  SyntheticScene tabletop;
  std::string scene_file, robot_scene_file, landmarks_dir, programs_dir;
  std::unique_ptr<serve::HttpServer> server;
  std::thread thread;
  std::unique_ptr<httplib::Client> client;
  int port = 0;
};

/// A connection to the test's server that sends whatever it is told, when it is told.
/// A connection to a server on this machine that sends whatever it is told, when it is told: a
/// slow sender.
class RawConnection {
 public:
  explicit RawConnection(int port);
  ~RawConnection();
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;

  bool connected() const { return connected_; }
  /// Whether the server still takes bytes (a cut-off connection is reset).
  bool send(const std::string& bytes);
  /// Everything the server sends until it closes the connection.
  std::string read_to_end();
  /// Whether the server has closed or reset the connection (looked at without waiting).
  bool closed_by_server() const;

 private:
  int sock_;
  bool connected_ = false;
};

/// A box as the API takes it: {position, quaternion [w,x,y,z], size}.
nlohmann::json box_json(const Box& box);

/// The JSON without its wall-clock times (keys starting "seconds"), at any depth.
nlohmann::json without_times(nlohmann::json j);

}  // namespace lmk::test
