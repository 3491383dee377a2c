// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target for lmk serve's request handling (issue #34): the access guard over any headers,
// and the API's handlers over any JSON body, name and query value, as the HTTP routes call them.
// Every input must give an answer (an ApiResponse, or ApiError / lmk::Error, which the server turns
// into its JSON error) whose JSON can be written: never a crash, a hang or a sanitizer report.
//
// Input: the first byte picks the route; the rest is split at its first '\n' into a name or query
// value and a body (or, for the guard, into the request's fields, one per line).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/serve/access_guard.h"
#include "lmk/serve/api.h"
#include "lmk/serve/api_error.h"
#include "tests/fuzz/fuzz_file.h"

namespace {

namespace fs = std::filesystem;
using lmk::serve::Api;
using lmk::serve::ApiResponse;

// One server for the whole run, over a small scene of its own: a table top and a box on it.
Api& api() {
  static const std::unique_ptr<Api> instance = [] {
    const fs::path dir = lmk::fuzz::scratch_dir();
    lmk::PointCloud scene;
    for (int i = 0; i < 40; ++i) {
      for (int j = 0; j < 40; ++j) {
        scene.points.emplace_back(-0.2f + 0.01f * i, -0.2f + 0.01f * j, 1.0f);
        if (i > 15 && i < 25 && j > 15 && j < 25) {
          scene.points.emplace_back(-0.2f + 0.01f * i, -0.2f + 0.01f * j, 0.9f);
        }
      }
    }
    scene.set_unorganized();
    const std::string file = (dir / "scene.pcd").string();
    lmk::write_cloud(file, scene);
    fs::create_directories(dir / "programs");
    lmk::serve::ServeSettings settings;
    settings.scenes = {file};
    settings.landmarks_dir = (dir / "landmarks").string();
    settings.programs_dir = (dir / "programs").string();
    settings.workers = 1;
    fs::create_directories(dir / "uploads");
    return std::make_unique<Api>(settings, dir / "uploads");
  }();
  return *instance;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

ApiResponse guard(const std::string& text) {
  std::vector<std::string> f = lines(text);
  f.resize(9);
  static const lmk::serve::AccessGuard access("fuzz-token-0123", "127.0.0.1", {"lab.local"});
  lmk::serve::RequestView r;
  r.method = f[0];
  r.path = f[1];
  r.host = f[2];
  r.origin = f[3];
  r.content_type = f[4];
  r.authorization = f[5];
  r.cookie = f[6];
  r.has_query_token = !f[7].empty();
  r.query_token = f[7];
  r.has_body = !f[8].empty();
  const lmk::serve::AccessVerdict v = access.check(r);
  return {v.allowed() ? 200 : v.status, {{"error", v.error}}};
}

// A body that would make the handler wait for a job (with "wait": true, or a capture's "check")
// waits no more: jobs run in the background, and a fuzz input must not wait on a queue of them.
std::string without_waiting(const std::string& body) {
  nlohmann::json j = nlohmann::json::parse(body, nullptr, false);
  if (!j.is_object()) return body;
  if (j.contains("wait")) j["wait"] = false;
  if (j.contains("check")) j["check"] = false;
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// The cloud download's pieces, put together: they must make one JSON answer.
ApiResponse streamed(lmk::serve::CloudDownload download) {
  std::string text;
  for (std::string piece = download.next(1000); !piece.empty(); piece = download.next(1000)) {
    text += piece;
  }
  nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || j["points"] != download.points()) __builtin_trap();
  return {200, j};
}

// The routes that answer without starting a job: a job still running when the process exits
// would outlive what it uses (check, find and plan start one; their bodies go through the same
// parsers in guess, capture and the cloud download).
ApiResponse route(std::uint8_t which, const std::string& name, const std::string& body) {
  Api& a = api();
  switch (which % 11) {
    case 0:
      return a.guess(body);
    case 1:
      return a.save_landmark(without_waiting(body));
    case 2:
      return streamed(a.scene_cloud(name, body));
    case 3:
      return a.job(name, "0");
    case 4:
      return a.upload_scene(name, body);
    case 5:
      return a.scene(name);
    case 6:
      return a.landmark(name);
    case 7:
      return a.program(name);
    case 8:
      return a.cancel_job(name);
    case 9:
      return a.info();
    default:
      return guard(name + "\n" + body);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  const std::size_t newline = text.find('\n');
  const std::string name = text.substr(0, newline);
  const std::string body = newline == std::string::npos ? "" : text.substr(newline + 1);
  ApiResponse response;
  try {
    response = route(data[0], name, body);
  } catch (const lmk::serve::ApiError& e) {
    response = {e.status(), {{"error", e.what()}}};
  } catch (const lmk::Error& e) {
    response = {422, {{"error", e.what()}}};
  } catch (const std::exception& e) {
    response = {500, {{"error", e.what()}}};  // the server answers it and goes on
  }
  // As the server writes it: any byte that is not UTF-8 replaced, so the answer stays JSON.
  const std::string written =
      response.body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (written.empty()) __builtin_trap();
  return 0;
}
