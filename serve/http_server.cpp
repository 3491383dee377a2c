// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/serve/http_server.h"

#include <stdlib.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <optional>

#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/error.h"
#include "lmk/serve/access_guard.h"
#include "lmk/serve/api_error.h"
#include "lmk/serve/connection_limits.h"
#include "lmk/serve/detail/guarded_server.h"
#include "lmk/serve/static_files.h"

// After Eigen: glibc's <resolv.h>, which httplib includes, defines `_res`, a name Eigen uses.
#include <httplib.h>

namespace lmk::serve {
namespace {

namespace fs = std::filesystem;

constexpr char kScratchPrefix[] = "lmk-serve-";

// Removes the scratch directories of servers that are gone: a crashed or killed server cannot
// remove its own (issue #34, finding 5). Their names carry the server's process id; a live
// server's, another user's and names of any other form are left alone.
void remove_stale_scratch_dirs(const fs::path& temp) {
  std::error_code ec;
  for (fs::directory_iterator it(temp, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(kScratchPrefix, 0) != 0) continue;
    const std::string rest = name.substr(sizeof(kScratchPrefix) - 1);
    const std::size_t dash = rest.find('-');
    if (dash == 0 || dash == std::string::npos || dash > 9 ||
        !std::all_of(rest.begin(), rest.begin() + dash,
                     [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; })) {
      continue;
    }
    struct stat info {};
    if (::lstat(it->path().c_str(), &info) != 0 || !S_ISDIR(info.st_mode) ||
        info.st_uid != ::getuid()) {
      continue;
    }
    if (process_has_ended(std::stol(rest.substr(0, dash)))) {
      std::error_code ignored;
      fs::remove_all(it->path(), ignored);
    }
  }
}

// A private directory for parsing uploads, named after this process and removed with the server.
fs::path make_scratch_dir() {
  const fs::path temp = fs::temp_directory_path();
  remove_stale_scratch_dirs(temp);
  std::string pattern = (temp / (kScratchPrefix + std::to_string(::getpid()) + "-XXXXXX")).string();
  if (mkdtemp(pattern.data()) == nullptr) {
    throw Error("cannot create a scratch directory in " + temp.string());
  }
  return pattern;
}

// Connections the kernel holds for the server before it accepts them: more than the HTTP threads,
// so that a burst of clients (the page's requests, scripts, the load test's 70) is queued, not
// dropped.
constexpr int kListenBacklog = 256;

// HTTP threads: each open connection holds one.
constexpr int kHttpThreads = 64;

constexpr const char* kJsonContentType = "application/json; charset=utf-8";

void send(httplib::Response& res, const ApiResponse& r) {
  res.status = r.status;
  // With a charset, httplib leaves the body uncompressed. Its brotli, which browsers ask for,
  // takes 10 s over a Kinect frame's points; over loopback the plain 5 MB arrive at once. A byte
  // that is not UTF-8 in a message becomes U+FFFD instead of an exception: the answer stays JSON.
  res.set_content(r.body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace),
                  kJsonContentType);
}

// The request's decoded path and query, when one of them is not UTF-8: the API's names and
// messages are JSON text, which must be (issue #34, finding 5: %ff gave 500 and a body that was
// not JSON).
std::optional<std::string> not_utf8_part(const httplib::Request& req) {
  if (!is_valid_utf8(req.path)) return "path";
  for (const auto& [key, value] : req.params) {
    if (!is_valid_utf8(key) || !is_valid_utf8(value)) return "query";
  }
  return std::nullopt;
}

// An error's message as a client gets it: what it echoes is cut (each site at kEchoedBytes, and
// the whole here) and escaped, whoever prints the body.
std::string error_text(const std::string& message) { return printable(message, 5 * kEchoedBytes); }

// Runs a request's handler; whatever it throws becomes the request's JSON error.
template <class F>
void guarded(httplib::Response& res, F&& handle) {
  try {
    handle();
  } catch (const ApiError& e) {
    nlohmann::json body = {{"error", error_text(e.what())}};
    if (e.details().is_object()) body.update(e.details());
    send(res, {e.status(), body});
    if (e.retry_after() > 0) res.set_header("Retry-After", std::to_string(e.retry_after()));
  } catch (const Error& e) {
    send(res, {422, {{"error", error_text(e.what())}}});
  } catch (const std::exception& e) {
    send(res, {500, {{"error", "internal error: " + error_text(e.what())}}});
  }
}

std::string reason_for(int status, const ServeSettings& s) {
  switch (status) {
    case 404:
      return "no such page or endpoint (docs/serve.md lists the API)";
    case 413:
      return "the upload is larger than the limit of " + std::to_string(s.max_upload_bytes >> 20) +
             " MiB (lmk serve --max-upload)";
    case 405:
      return "method not allowed here";
    default:
      return "request failed (HTTP " + std::to_string(status) + ")";
  }
}

// The reservation of the JSON body the current request's thread is reading and parsing: held from
// the headers until the handler has answered (or, when no handler ran, until the logger, which
// runs for every reply, lets it go).
thread_local MemoryBudget::Reservation json_body_memory;

// The body length a request declares (Content-Length); 0 when it declares none.
unsigned long long declared_length(const httplib::Request& req) {
  return std::strtoull(req.get_header_value("Content-Length").c_str(), nullptr, 10);
}

RequestView view_of(const httplib::Request& req) {
  RequestView v;
  v.method = req.method;
  v.path = req.path;
  v.host = req.get_header_value("Host");
  v.origin = req.get_header_value("Origin");
  v.content_type = req.get_header_value("Content-Type");
  v.authorization = req.get_header_value("Authorization");
  v.cookie = req.get_header_value("Cookie");
  v.has_query_token = req.has_param("token");
  v.has_body = req.has_header("Transfer-Encoding") || declared_length(req) > 0;
  if (v.has_query_token) v.query_token = req.get_param_value("token");
  return v;
}

// The guard of `settings`: its token, or a fresh one unless it asks none.
AccessGuard make_guard(const ServeSettings& s) {
  if (s.no_token && !is_loopback_name(s.bind)) {
    throw Error("--no-token is only allowed on a loopback address; with --bind " + s.bind +
                " anyone who reaches it could write landmarks");
  }
  const std::string token = s.no_token ? "" : (s.token.empty() ? random_token() : s.token);
  return AccessGuard(token, s.bind, s.allowed_hosts);
}

}  // namespace

struct HttpServer::Impl {
  Impl(ServeSettings settings, std::ostream* log_in)
      : guard(make_guard(settings)),
        scratch(make_scratch_dir()),
        api(std::move(settings), scratch),
        log(log_in),
        connections(api.settings().connections) {}
  ~Impl() {
    std::error_code ignored;
    fs::remove_all(scratch, ignored);
  }

  void routes();
  void api_routes();
  void page_routes();
  void reply_and_log_settings();
  void guard_requests();
  void reserve_json_body(const httplib::Request& req);
  ApiResponse upload(const httplib::Request& req, const httplib::ContentReader& read,
                     std::string name);
  void api_route(const char* method, const std::string& pattern,
                 std::function<ApiResponse(const httplib::Request&)> handle);

  AccessGuard guard;
  fs::path scratch;
  Api api;
  std::ostream* log;
  std::mutex log_mutex;
  ConnectionTable connections;
  detail::GuardedServer server{connections};
};

void HttpServer::Impl::api_route(const char* method, const std::string& pattern,
                                 std::function<ApiResponse(const httplib::Request&)> handle) {
  auto handler = [handle](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] { send(res, handle(req)); });
    json_body_memory.release();  // parsed and answered, before httplib writes the reply
  };
  if (std::string(method) == "GET") {
    server.Get(pattern, handler);
  } else if (std::string(method) == "DELETE") {
    server.Delete(pattern, handler);
  } else {
    server.Post(pattern, handler);
  }
}

// A JSON body is bounded by --max-json and reserved in the memory budget before httplib reads it
// (issue #61, finding 4: four concurrent 250 MB bodies peaked at 3.26 GB with the budget showing
// nothing in use). ApiError 411, 413 or 503.
void HttpServer::Impl::reserve_json_body(const httplib::Request& req) {
  json_body_memory.release();
  const bool upload = req.method == "POST" && req.path == "/api/scenes";
  if (req.method == "GET" || upload || req.path.rfind("/api/", 0) != 0) return;
  if (req.has_header("Transfer-Encoding")) {
    throw ApiError(411, "a JSON body must declare its Content-Length");
  }
  const std::size_t most = api.settings().max_json_bytes;
  const unsigned long long length = declared_length(req);
  if (length > most) {
    throw ApiError(413, "the JSON body is " + std::to_string(length) + " bytes; at most " +
                            std::to_string(most) + " (lmk serve --max-json)");
  }
  json_body_memory = api.budget().reserve(json_body_price(static_cast<std::size_t>(length)),
                                          "requests", "a JSON body");
}

// Every request passes the access guard before it is routed, and before its body is read.
void HttpServer::Impl::guard_requests() {
  server.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    // The headers are in: the body, if any, is due at the least rate from now.
    if (ConnectionTable::Connection* c = ConnectionTable::current()) {
      const bool chunked = req.has_header("Transfer-Encoding");
      connections.headers_read(
          *c, chunked ? api.settings().max_upload_bytes
                      : static_cast<std::size_t>(std::min<unsigned long long>(
                            declared_length(req), api.settings().max_upload_bytes)));
    }
    const AccessVerdict verdict = guard.check(view_of(req));
    if (verdict.authenticated) {
      if (ConnectionTable::Connection* c = ConnectionTable::current())
        connections.authenticated(*c);
    }
    if (!verdict.allowed()) {
      send(res, {verdict.status, {{"error", verdict.error}}});
      return httplib::Server::HandlerResponse::Handled;
    }
    try {
      reserve_json_body(req);
    } catch (const ApiError&) {
      const std::exception_ptr refusal = std::current_exception();
      guarded(res, [&refusal] { std::rethrow_exception(refusal); });
      return httplib::Server::HandlerResponse::Handled;
    }
    if (const auto part = not_utf8_part(req)) {
      send(res, {400, {{"error", "the request's " + *part + " is not valid UTF-8"}}});
      return httplib::Server::HandlerResponse::Handled;
    }
    if (verdict.token_from_query && req.path == "/") {
      // The page keeps the token in its cookie, and the address bar loses it.
      res.set_header("Set-Cookie", guard.set_cookie_value());
      res.set_redirect("/", 303);
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });
}

// Writes an upload's cloud to a scratch file as it arrives, at most --max-upload bytes of it, and
// hands the file to the API: no upload is ever whole in memory before it is priced and parsed.
ApiResponse HttpServer::Impl::upload(const httplib::Request& req,
                                     const httplib::ContentReader& read, std::string name) {
  const std::size_t limit = api.settings().max_upload_bytes;
  std::unique_ptr<UploadFile> file;
  std::optional<ApiError> refused;  // a bad name: the body is read (and dropped) first, so that
                                    // the client, still sending, gets the answer
  std::size_t received = 0;
  bool over = false;
  bool collecting = true;  // in a form, only while its file's part arrives
  const auto receive = [&](const char* data, std::size_t n) {
    if (!collecting) return true;
    over = received + n > limit;
    if (over) return false;
    received += n;
    if (!file && !refused) {
      try {
        file = api.new_upload_file(name);
      } catch (const ApiError& e) {
        refused = e;
      }
    }
    if (file) file->write(data, n);
    return true;
  };
  bool complete = false;
  if (req.is_multipart_form_data()) {
    int files = 0;
    complete = read(
        [&](const httplib::MultipartFormData& part) {
          collecting = !part.filename.empty();  // not a form's text field
          if (!collecting) return true;
          if (name.empty()) name = part.filename;
          return ++files == 1;  // a second file stops the reading (httplib's callbacks)
        },
        receive);
    if (files != 1) {
      throw bad_request(files == 0 ? "upload: the form holds no file"
                                   : "upload: the form holds more than one file");
    }
  } else {
    complete = read(receive);
  }
  // httplib refuses a declared length over the limit before reading: nothing arrives.
  if (over || declared_length(req) > limit) throw ApiError(413, reason_for(413, api.settings()));
  if (refused) throw *refused;
  if (!complete) throw bad_request("upload: the body was cut short");
  if (!file) file = api.new_upload_file(name);  // an empty file: the reader says so
  return api.upload_scene(*file);
}

void HttpServer::Impl::routes() {
  guard_requests();
  api_routes();
  page_routes();
  reply_and_log_settings();
}

// Every /api path, to Api.
void HttpServer::Impl::api_routes() {
  Api& a = api;
  const auto param = [](const httplib::Request& r, const char* key) {
    return r.has_param(key) ? r.get_param_value(key) : std::string();
  };
  api_route("GET", "/api/info", [this, &a](const auto&) {
    ApiResponse info = a.info();
    info.body["connections"] = {{"open", connections.open_connections()},
                                {"cut_off", connections.cut_off_connections()}};
    return info;
  });
  api_route("GET", "/api/health", [](const auto&) { return Api::health(); });
  api_route("DELETE", "/api/jobs/(.+)", [&a](const auto& r) { return a.cancel_job(r.matches[1]); });
  api_route("GET", "/api/scenes", [&a](const auto&) { return a.scenes(); });
  // An upload's body is the cloud file itself, whatever Content-Type the client put on it: curl's
  // --data-binary says application/x-www-form-urlencoded, whose bodies httplib would otherwise
  // parse as a form and cap at 8 KB (issue #34, finding 6). A content reader takes the bytes as
  // they come; a multipart form (an HTML form's upload) gives the content of its one file.
  server.Post("/api/scenes", [this, param](const httplib::Request& req, httplib::Response& res,
                                           const httplib::ContentReader& read) {
    guarded(res, [&] { send(res, upload(req, read, param(req, "name"))); });
  });
  api_route("GET", "/api/scenes/([^/]+)", [&a](const auto& r) { return a.scene(r.matches[1]); });
  // The cloud is written a piece at a time as the client reads it, never whole in memory.
  server.Get("/api/scenes/([^/]+)/cloud", [&a, param](const auto& req, httplib::Response& res) {
    guarded(res, [&] {
      auto download =
          std::make_shared<CloudDownload>(a.scene_cloud(req.matches[1], param(req, "max_points")));
      res.status = 200;
      res.set_chunked_content_provider(kJsonContentType,
                                       [download](std::size_t, httplib::DataSink& sink) {
                                         const std::string piece = download->next();
                                         if (piece.empty()) {
                                           sink.done();
                                         } else if (!sink.write(piece.data(), piece.size())) {
                                           return false;  // the client went away
                                         }
                                         return true;
                                       });
    });
  });
  api_route("POST", "/api/guess", [&a](const auto& r) { return a.guess(r.body); });
  api_route("POST", "/api/check", [&a](const auto& r) { return a.check(r.body); });
  api_route("GET", "/api/landmarks", [&a](const auto&) { return a.landmarks(); });
  api_route("POST", "/api/landmarks", [&a](const auto& r) { return a.save_landmark(r.body); });
  api_route("GET", "/api/landmarks/(.+)", [&a](const auto& r) { return a.landmark(r.matches[1]); });
  api_route("POST", "/api/find", [&a](const auto& r) { return a.find(r.body); });
  api_route("GET", "/api/jobs/(.+)",
            [&a, param](const auto& r) { return a.job(r.matches[1], param(r, "wait")); });
  api_route("GET", "/api/programs", [&a](const auto&) { return a.programs(); });
  api_route("GET", "/api/programs/(.+)", [&a](const auto& r) { return a.program(r.matches[1]); });
  api_route("POST", "/api/programs/(.+)/plan",
            [&a](const auto& r) { return a.plan(r.matches[1], r.body); });
}

// The page, its scripts and three.js.
void HttpServer::Impl::page_routes() {
  const auto file = [](httplib::Response& res, const StaticFile& f) {
    res.set_content(f.body, f.content_type.c_str());
  };
  server.Get("/", [file](const httplib::Request&, httplib::Response& res) {
    guarded(res, [&] { file(res, web_asset("index.html")); });
  });
  server.Get("/app/(.+)", [file](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] { file(res, web_asset(req.matches[1])); });
  });
  const fs::path three = api.settings().three_dir.empty() ? fs::path(LMK_THREE_DIR)
                                                          : fs::path(api.settings().three_dir);
  server.Get("/three/(.*)", [file, three](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] { file(res, confined_file(three, req.matches[1])); });
  });
}

// JSON replies for the statuses httplib sets itself and for exceptions, the body limit, the log
// and the thread pool.
void HttpServer::Impl::reply_and_log_settings() {
  // Statuses httplib sets itself (404 for no route, 413 for an oversized body) get a JSON reason.
  const ServeSettings& settings = api.settings();
  server.set_error_handler([&settings](const httplib::Request&, httplib::Response& res) {
    if (!res.body.empty()) return;
    send(res, {res.status, {{"error", reason_for(res.status, settings)}}});
  });
  server.set_exception_handler(
      [](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
        send(res, {500, {{"error", "internal error"}}});
      });
  server.set_payload_max_length(settings.max_upload_bytes);
  server.set_logger([this](const httplib::Request& req, const httplib::Response& res) {
    json_body_memory.release();  // the reply is written: the body and its parse are gone
    if (log != nullptr) {
      if (req.path.rfind("/api/", 0) != 0 && res.status < 400) return;       // the page's own files
      if (req.path.rfind("/api/jobs/", 0) == 0 && res.status < 400) return;  // polling
      // The path is the client's, URL-decoded: escaped, or it could clear the operator's
      // terminal, set its title or forge a log line (issue #47).
      std::string line = printable(req.method, 16) + " " + printable(req.path, kEchoedBytes) + " " +
                         std::to_string(res.status);
      if (res.status >= 400) line += " " + printable(res.body, 2 * kEchoedBytes);
      std::lock_guard<std::mutex> lock(log_mutex);
      *log << line << std::endl;
    }
  });
  // Enough threads that the page stays answered while requests wait for searches, and while one
  // client's slow connections hold the most that ConnectionLimits lets them (16 by default).
  server.new_task_queue = [] { return new httplib::ThreadPool(kHttpThreads); };
}

HttpServer::HttpServer(ServeSettings settings, std::ostream* log)
    : impl_(std::make_unique<Impl>(std::move(settings), log)) {
  impl_->routes();
}

HttpServer::~HttpServer() { stop(); }

int HttpServer::bind() {
  const ServeSettings& s = impl_->api.settings();
  // httplib listens with a backlog of 5 connections: of 50 clients connecting at once, some found
  // the queue full and got no answer (issue #34's load test). Linux takes a second listen() on a
  // listening socket as a new backlog, so the socket is kept from httplib's options callback.
  int listening = -1;
  impl_->server.set_socket_options([&listening](socket_t sock) {
    httplib::default_socket_options(sock);
    listening = sock;
  });
  const int port = s.port == 0 ? impl_->server.bind_to_any_port(s.bind)
                               : (impl_->server.bind_to_port(s.bind, s.port) ? s.port : -1);
  if (port < 0) {
    throw Error("cannot listen on " + s.bind + ":" + std::to_string(s.port) +
                " (in use, or not an address of this machine); choose another with --port");
  }
  if (listening >= 0) ::listen(listening, kListenBacklog);
  impl_->guard.set_port(port);
  return port;
}

void HttpServer::run() { impl_->server.listen_after_bind(); }

void HttpServer::stop() {
  // The jobs first: requests waiting for one return at once, so httplib's stop, which waits for
  // every request under way, does not wait for a search (Ctrl-C took 22 s, issue #34, finding 3).
  impl_->api.stop();
  if (impl_->server.is_running()) impl_->server.stop();
}

bool HttpServer::jobs_ended_within(double seconds) { return impl_->api.jobs_ended_within(seconds); }

Api& HttpServer::api() { return impl_->api; }

const std::string& HttpServer::token() const { return impl_->guard.token(); }

}  // namespace lmk::serve
