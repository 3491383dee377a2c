// SPDX-License-Identifier: BSD-3-Clause
// Who may drive lmk serve (docs/serve.md, "Access"; issue #34, finding 1): a web page the user
// visits, a name rebound to 127.0.0.1 and a client without the token are refused before anything
// is read or written; the page and API clients with the token work as before.
#include <filesystem>
#include <set>
#include <vector>

#include "lmk/geometry/error.h"
#include "lmk/serve/access_guard.h"
#include "tests/serve/serve_fixture.h"

namespace lmk::test {
namespace {

namespace fs = std::filesystem;
using serve::AccessGuard;
using serve::RequestView;

RequestView request(const std::string& method, const std::string& path,
                    const std::string& host = "127.0.0.1:8080") {
  RequestView r;
  r.method = method;
  r.path = path;
  r.host = host;
  r.authorization = "token secret-token";
  if (method == "POST") r.content_type = "application/json";
  return r;
}

TEST(AccessGuard, HostNamesAreTakenWithoutPortOrBrackets) {
  EXPECT_EQ(serve::host_name_of("127.0.0.1:8080"), "127.0.0.1");
  EXPECT_EQ(serve::host_name_of("LocalHost"), "localhost");
  EXPECT_EQ(serve::host_name_of("[::1]:8080"), "::1");
  EXPECT_EQ(serve::host_name_of("::1"), "::1");
  EXPECT_EQ(serve::host_name_of("rebind.evil.example:8080"), "rebind.evil.example");
  EXPECT_EQ(serve::host_name_of("[::1"), "");
  EXPECT_TRUE(serve::is_loopback_name("127.0.0.1"));
  EXPECT_TRUE(serve::is_loopback_name("127.1.2.3"));
  EXPECT_TRUE(serve::is_loopback_name("::1"));
  EXPECT_FALSE(serve::is_loopback_name("127.0.0.1.evil.example"));
  EXPECT_FALSE(serve::is_loopback_name("0.0.0.0"));
}

TEST(AccessGuard, OnlyLoopbackTheBoundAddressAndAllowedNamesReachIt) {
  const AccessGuard loopback("secret-token", "127.0.0.1", {"lab-pc.local"});
  for (const std::string host :
       {"127.0.0.1:8080", "localhost:8080", "[::1]:8080", "LOCALHOST", "lab-pc.local:8080"}) {
    EXPECT_TRUE(loopback.check(request("GET", "/api/info", host)).allowed()) << host;
  }
  for (const std::string host :
       {"rebind.evil.example:8080", "10.0.0.5:8080", "", "[::1", "127.0.0.1.evil.example"}) {
    const auto v = loopback.check(request("GET", "/api/info", host));
    EXPECT_EQ(v.status, 403) << host;
  }
  // Listening on every address: any address written out (it cannot be rebound), never a name.
  const AccessGuard everywhere("secret-token", "0.0.0.0", {});
  EXPECT_TRUE(everywhere.check(request("GET", "/api/info", "10.0.0.5:8080")).allowed());
  EXPECT_TRUE(everywhere.check(request("GET", "/api/info", "[fe80::1]:8080")).allowed());
  EXPECT_EQ(everywhere.check(request("GET", "/api/info", "rebind.evil.example:8080")).status, 403);
  const AccessGuard bound("secret-token", "192.168.1.20", {});
  EXPECT_TRUE(bound.check(request("GET", "/api/info", "192.168.1.20:8080")).allowed());
  EXPECT_EQ(bound.check(request("GET", "/api/info", "192.168.1.21:8080")).status, 403);
}

TEST(AccessGuard, TheTokenComesFromTheHeaderTheCookieOrThePagesAddress) {
  AccessGuard guard("secret-token", "127.0.0.1", {});
  guard.set_port(8080);
  EXPECT_EQ(guard.cookie_name(), "lmk_token_8080");
  RequestView r = request("GET", "/api/info");
  EXPECT_TRUE(guard.check(r).allowed());
  r.authorization = "Bearer secret-token";
  EXPECT_TRUE(guard.check(r).allowed());
  r.authorization = "token secret-tokeN";
  EXPECT_EQ(guard.check(r).status, 401);
  EXPECT_NE(guard.check(r).error.find("wrong token"), std::string::npos);
  r.authorization.clear();
  EXPECT_EQ(guard.check(r).status, 401);
  EXPECT_NE(guard.check(r).error.find("needs its token"), std::string::npos);
  r.cookie = "other=1; lmk_token_8080=secret-token; more=2";
  EXPECT_TRUE(guard.check(r).allowed());
  EXPECT_FALSE(guard.check(r).token_from_query);
  r.cookie = "lmk_token_9090=secret-token";  // another server's cookie
  EXPECT_EQ(guard.check(r).status, 401);
  r.cookie.clear();
  // The page's address carries the token once; the API never takes it from the address (issue
  // #61, finding 7), even right.
  RequestView page = request("GET", "/");
  page.authorization.clear();
  page.has_query_token = true;
  page.query_token = "secret-token";
  EXPECT_TRUE(guard.check(page).allowed());
  EXPECT_TRUE(guard.check(page).token_from_query);
  page.query_token = "secret";
  EXPECT_EQ(guard.check(page).status, 401);
  r.has_query_token = true;
  r.query_token = "secret-token";
  EXPECT_EQ(guard.check(r).status, 401);
  EXPECT_NE(guard.check(r).error.find("never in the address"), std::string::npos);
  r.authorization = "token secret-token";  // the header does not make the address right
  EXPECT_EQ(guard.check(r).status, 401);
  // The page's code and three.js carry no secret: they need no token.
  RequestView asset = request("GET", "/app/app.js");
  asset.authorization.clear();
  EXPECT_TRUE(guard.check(asset).allowed());
  asset.path = "/";
  EXPECT_EQ(guard.check(asset).status, 401);
  const std::string cookie = guard.set_cookie_value();
  for (const std::string part : {"lmk_token_8080=secret-token", "HttpOnly", "SameSite=Strict"}) {
    EXPECT_NE(cookie.find(part), std::string::npos) << cookie;
  }
}

TEST(AccessGuard, StateChangesComeFromTheServersOwnPageAsJson) {
  const AccessGuard guard("secret-token", "127.0.0.1", {});
  RequestView r = request("POST", "/api/landmarks");
  r.origin = "http://127.0.0.1:8080";
  EXPECT_TRUE(guard.check(r).allowed());
  r.origin = "http://evil.example";
  EXPECT_EQ(guard.check(r).status, 403);
  r.origin = "null";  // a sandboxed frame, a file:// page
  EXPECT_EQ(guard.check(r).status, 403);
  r.origin = "http://127.0.0.1:9999";  // another server of this machine
  EXPECT_EQ(guard.check(r).status, 403);
  r.origin.clear();  // not a browser: the token decides
  EXPECT_TRUE(guard.check(r).allowed());
  for (const std::string type :
       {"text/plain", "application/x-www-form-urlencoded", "multipart/form-data; boundary=x", ""}) {
    r.content_type = type;
    EXPECT_EQ(guard.check(r).status, 415) << type;
  }
  r.content_type = "Application/JSON; charset=utf-8";
  EXPECT_TRUE(guard.check(r).allowed());
  // An upload's body is a cloud, whatever its type.
  RequestView upload = request("POST", "/api/scenes");
  upload.content_type = "application/octet-stream";
  EXPECT_TRUE(guard.check(upload).allowed());
  // A GET changes nothing: a cross-origin page cannot read its answer anyway.
  RequestView get = request("GET", "/api/scenes");
  get.origin = "http://evil.example";
  EXPECT_TRUE(guard.check(get).allowed());
}

TEST(AccessGuard, TokensAreRandomAndComparedWhole) {
  std::set<std::string> tokens;
  for (int i = 0; i < 20; ++i) tokens.insert(serve::random_token());
  EXPECT_EQ(tokens.size(), 20u);
  EXPECT_EQ(tokens.begin()->size(), 48u);
  EXPECT_TRUE(serve::equal_in_constant_time("abc", "abc"));
  EXPECT_FALSE(serve::equal_in_constant_time("abc", "abd"));
  EXPECT_FALSE(serve::equal_in_constant_time("abc", "abcd"));
  EXPECT_FALSE(serve::equal_in_constant_time("", "a"));
  for (const std::string bad :
       {"short", "with space in it", "semi;colon-token", "new\nline-token"}) {
    EXPECT_THROW(AccessGuard(bad, "127.0.0.1", {}), Error) << bad;
  }
}

// Over HTTP, the issue's own requests.
httplib::Headers headers(std::initializer_list<std::pair<const std::string, std::string>> list) {
  return httplib::Headers(list);
}

TEST_F(ServeTest, ACrossSitePageCannotWriteALandmark) {
  start();
  const std::string body = nlohmann::json{
      {"scene", "1"},
      {"name", "x"},
      {"overwrite", true},
      {"box",
       box_json(carton_box())}}.dump();
  httplib::Client bare("127.0.0.1", port);  // what a browser sends for another site: no token
  const auto no_token =
      bare.Post("/api/landmarks", headers({{"Origin", "http://evil.example"}}), body, "text/plain");
  ASSERT_TRUE(no_token);
  EXPECT_EQ(no_token->status, 403) << no_token->body;
  // Even with the token (leaked, say), a foreign Origin or a text/plain body changes nothing.
  const auto foreign = client->Post("/api/landmarks", headers({{"Origin", "http://evil.example"}}),
                                    body, "application/json");
  ASSERT_TRUE(foreign);
  EXPECT_EQ(foreign->status, 403);
  const auto plain = client->Post("/api/landmarks", body, "text/plain");
  ASSERT_TRUE(plain);
  EXPECT_EQ(plain->status, 415);
  EXPECT_NE(plain->body.find("application/json"), std::string::npos) << plain->body;
  const auto without = bare.Post("/api/landmarks", body, "application/json");
  ASSERT_TRUE(without);
  EXPECT_EQ(without->status, 401);
  EXPECT_FALSE(fs::exists(fs::path(landmarks_dir) / "x.lmk"));
  // The server's own page may.
  const auto own = client->Post("/api/landmarks",
                                headers({{"Origin", "http://127.0.0.1:" + std::to_string(port)}}),
                                body, "application/json");
  ASSERT_TRUE(own);
  EXPECT_EQ(own->status, 201) << own->body;
  EXPECT_TRUE(fs::exists(fs::path(landmarks_dir) / "x.lmk"));
}

TEST_F(ServeTest, ARebindingNameIsRefused) {
  start();
  for (const std::string path : {"/api/scenes", "/"}) {
    const auto r =
        client->Get(path, headers({{"Host", "rebind.evil.example:" + std::to_string(port)}}));
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 403) << path;
    EXPECT_EQ(r->body.find("carton"), std::string::npos);
  }
  EXPECT_EQ(get("/api/scenes").status, 200);
}

TEST_F(ServeTest, ThePageKeepsThePrintedTokenInACookie) {
  start();
  httplib::Client browser("127.0.0.1", port);
  EXPECT_EQ(browser.Get("/")->status, 401);
  EXPECT_EQ(browser.Get("/?token=wrong-token")->status, 401);
  const auto first = browser.Get(("/?token=" + server->token()).c_str());
  ASSERT_TRUE(first);
  EXPECT_EQ(first->status, 303);
  EXPECT_EQ(first->get_header_value("Location"), "/");
  const std::string cookie = first->get_header_value("Set-Cookie");
  const std::string pair = "lmk_token_" + std::to_string(port) + "=" + server->token();
  ASSERT_EQ(cookie.rfind(pair, 0), 0u) << cookie;
  EXPECT_NE(cookie.find("SameSite=Strict"), std::string::npos);
  const auto page = browser.Get("/", headers({{"Cookie", pair}}));
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("<title>lmk serve</title>"), std::string::npos);
  const auto info = browser.Get("/api/info", headers({{"Cookie", pair}}));
  ASSERT_TRUE(info);
  EXPECT_EQ(info->status, 200);
}

TEST_F(ServeTest, TheTokenCanBeChosenOrTurnedOffOnLoopbackOnly) {
  serve::ServeSettings chosen;
  chosen.token = "my-own-token";
  start(chosen);
  EXPECT_EQ(server->token(), "my-own-token");
  httplib::Client bare("127.0.0.1", port);
  EXPECT_EQ(bare.Get("/api/info", headers({{"Authorization", "token my-own-token"}}))->status, 200);
  TearDown();

  serve::ServeSettings open;
  open.no_token = true;
  start(open);
  EXPECT_TRUE(server->token().empty());
  httplib::Client anyone("127.0.0.1", port);
  EXPECT_EQ(anyone.Get("/api/info")->status, 200);
  // The other checks still hold.
  EXPECT_EQ(anyone.Post("/api/guess", "{}", "text/plain")->status, 415);
  TearDown();

  serve::ServeSettings exposed;
  exposed.no_token = true;
  exposed.bind = "0.0.0.0";
  exposed.scenes = {scene_file};
  exposed.landmarks_dir = landmarks_dir;
  try {
    serve::HttpServer refused(exposed);
    ADD_FAILURE() << "--no-token was accepted on 0.0.0.0";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--no-token is only allowed on a loopback address"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(ServeTest, AnAllowedHostNameReachesIt) {
  serve::ServeSettings settings;
  settings.allowed_hosts = {"lab-pc.local"};
  start(settings);
  const auto r =
      client->Get("/api/info", headers({{"Host", "lab-pc.local:" + std::to_string(port)}}));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
}

// Every route of docs/serve.md: without the token 401, under a foreign Host 403, and for those
// that change state, 403 from a foreign Origin and 415 for a JSON body sent as text/plain; none of
// them changes anything.
TEST_F(ServeTest, EveryRouteIsGuarded) {
  start();
  struct Route {
    std::string method, path;
  };
  const std::vector<Route> routes = {
      {"GET", "/"},
      {"GET", "/api/info"},
      {"GET", "/api/health"},
      {"GET", "/api/scenes"},
      {"POST", "/api/scenes?name=new.pcd"},
      {"GET", "/api/scenes/1"},
      {"GET", "/api/scenes/1/cloud"},
      {"POST", "/api/guess"},
      {"POST", "/api/check"},
      {"GET", "/api/landmarks"},
      {"POST", "/api/landmarks"},
      {"GET", "/api/landmarks/carton"},
      {"POST", "/api/find"},
      {"GET", "/api/jobs/job-1"},
      {"DELETE", "/api/jobs/job-1"},
      {"GET", "/api/programs"},
      {"GET", "/api/programs/x"},
      {"POST", "/api/programs/x/plan"},
  };
  const std::string body =
      nlohmann::json{{"scene", "1"}, {"name", "x"}, {"box", box_json(carton_box())}}.dump();
  const std::string token = "token " + server->token();
  const std::string own_host = "127.0.0.1:" + std::to_string(port);
  httplib::Client c("127.0.0.1", port);
  const auto send = [&](const Route& r, httplib::Headers h, const std::string& type) {
    httplib::Result res = r.method == "GET"      ? c.Get(r.path.c_str(), h)
                          : r.method == "DELETE" ? c.Delete(r.path.c_str(), h)
                                                 : c.Post(r.path.c_str(), h, body, type.c_str());
    return res ? res->status : -1;
  };
  for (const Route& r : routes) {
    SCOPED_TRACE(r.method + " " + r.path);
    EXPECT_EQ(send(r, {}, "application/json"), 401);
    EXPECT_EQ(
        send(r, {{"Authorization", token}, {"Host", "rebind.evil.example"}}, "application/json"),
        403);
    if (r.method == "GET") continue;
    EXPECT_EQ(
        send(r, {{"Authorization", token}, {"Origin", "http://evil.example"}}, "application/json"),
        403);
    if (r.path.rfind("/api/scenes", 0) != 0 && r.method == "POST") {
      EXPECT_EQ(send(r, {{"Authorization", token}, {"Origin", "http://" + own_host}}, "text/plain"),
                415);
    }
  }
  EXPECT_FALSE(fs::exists(landmarks_dir) && !fs::is_empty(landmarks_dir));
  EXPECT_EQ(get("/api/scenes").body["scenes"].size(), 2u);
}

}  // namespace
}  // namespace lmk::test
