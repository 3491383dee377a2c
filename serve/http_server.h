// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// `lmk serve`'s HTTP side (cpp-httplib): routes every /api path to Api, serves the page and
// three.js, bounds uploads, and turns every failure of a request into a JSON error with its
// status, so that no request can stop the server.
#include <memory>
#include <ostream>
#include <string>

#include "lmk/serve/api.h"
#include "lmk/serve/serve_settings.h"

namespace lmk::serve {

class HttpServer {
 public:
  /// Reads the scenes and opens the directories (lmk::Error for bad ones, and for no_token off
  /// loopback or a malformed token). Every request passes an AccessGuard first. Requests are
  /// logged, one line each, to `log` unless it is null.
  explicit HttpServer(ServeSettings settings, std::ostream* log = nullptr);
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  /// Binds to settings.bind:settings.port and returns the port (the kernel's choice for port 0);
  /// lmk::Error naming the address when it cannot.
  int bind();
  /// Serves until stop() is called (from any thread). bind() first.
  void run();
  /// Stops serving: the jobs are told to end at their next progress report, waiting requests are
  /// answered, and run() returns once the requests under way are.
  void stop();
  /// After stop(): whether the jobs under way have ended within `seconds`. When one has not (a
  /// stage without progress reports), a process that must stop in time may exit regardless:
  /// nothing it writes is half-written.
  bool jobs_ended_within(double seconds);

  Api& api();
  /// The token every API request and the page must carry (docs/serve.md, "Access"); empty with
  /// settings.no_token.
  const std::string& token() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lmk::serve
