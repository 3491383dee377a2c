// SPDX-License-Identifier: BSD-3-Clause
// lmk serve's safety (docs/serve.md, "Safety"): files stay confined to the directories given,
// uploads are bounded, and no request, however bad, stops the server.
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

#include "lmk/geometry/cloud_io.h"
#include "tests/serve/serve_fixture.h"

namespace lmk::test {
namespace {

namespace fs = std::filesystem;

TEST_F(ServeTest, ThePageAndThreeJsAreServed) {
  start();
  const Reply page = get("/");
  ASSERT_EQ(page.status, 200);
  EXPECT_NE(page.text.find("<title>lmk serve</title>"), std::string::npos);
  const auto app = client->Get("/app/app.js");
  ASSERT_TRUE(app);
  EXPECT_EQ(app->status, 200);
  EXPECT_EQ(app->get_header_value("Content-Type"), "application/javascript; charset=utf-8");
  if (!fs::exists("/usr/share/javascript/three/build/three.module.js")) {
    GTEST_SKIP() << "libjs-three is not installed (scripts/install-deps.sh installs it)";
  }
  const auto three = client->Get("/three/build/three.module.js");
  ASSERT_TRUE(three);
  EXPECT_EQ(three->status, 200);
  EXPECT_NE(three->body.find("REVISION"), std::string::npos);
  EXPECT_EQ(get("/three/build/none.js").status, 404);
  EXPECT_EQ(get("/app/none.js").status, 404);
  EXPECT_EQ(get("/nowhere").status, 404);
}

TEST_F(ServeTest, PathTraversalIsRefusedAndNeverReadsTheFile) {
  // three.js from a directory of the test's, holding a link that leads out of it.
  const fs::path three = dir.path() / "three";
  fs::create_directories(three / "build");
  write_text((three / "build" / "three.module.js").string(), "export const REVISION = 'test';");
  write_text(dir.file("secret.txt"), "SECRET");
  fs::create_symlink(dir.path() / "secret.txt", three / "build" / "link.js");
  serve::ServeSettings settings;
  settings.three_dir = three.string();
  start(settings);
  EXPECT_EQ(get("/three/build/three.module.js").status, 200);
  for (const std::string path :
       {"/three/../secret.txt", "/three/%2e%2e/secret.txt", "/three/build/%2E%2E/%2E%2E/secret.txt",
        "/three/build/..%2f..%2fsecret.txt", "/three/build/link.js", "/three/%2fetc%2fpasswd",
        "/three/build/..\\..\\secret.txt", "/app/..%2f..%2fsecret.txt",
        "/api/landmarks/..%2f..%2fsecret.txt", "/api/landmarks/%2e%2e",
        "/api/programs/..%2fsecret"}) {
    const Reply r = get(path);
    EXPECT_TRUE(r.status == 400 || r.status == 403) << path << ": " << r.status << " " << r.text;
    EXPECT_EQ(r.text.find("SECRET"), std::string::npos) << path;
  }
  // The same through the JSON bodies: names that would leave the landmark directory.
  for (const std::string name : {"../secret", "/tmp/x", "a/b", ".hidden", ""}) {
    const Reply r =
        post("/api/landmarks", {{"scene", "1"}, {"name", name}, {"box", box_json(carton_box())}});
    EXPECT_EQ(r.status, 400) << name << ": " << r.text;
  }
  EXPECT_EQ(post("/api/find", {{"scene", "1"}, {"landmarks", {"../secret"}}}).status, 400);
  EXPECT_FALSE(fs::exists(dir.file("secret.lmk")));
}

TEST_F(ServeTest, AnOversizedUploadIsRefusedWithTheLimitAndTheServerGoesOn) {
  serve::ServeSettings settings;
  settings.max_upload_bytes = 1u << 20;
  start(settings);
  const std::string big(3u << 20, 'x');
  const Reply r = post_bytes("/api/scenes?name=big.pcd", big);
  EXPECT_EQ(r.status, 413) << r.text;
  if (r.status == 413) {
    EXPECT_NE(r.body["error"].get<std::string>().find("--max-upload"), std::string::npos);
  }
  EXPECT_EQ(get("/api/scenes").body["scenes"].size(), 2u);
  EXPECT_EQ(get("/api/info").status, 200);
}

// Issue #34, finding 6: curl's --data-binary labels the body a form, whose bodies httplib capped at
// 8 KB, so the documented upload got 413 "larger than the limit of 256 MiB".
TEST_F(ServeTest, TheDocumentedCurlUploadWorksWhateverTheContentType) {
  start();
  const std::string pcd = read_bytes(scene_file);
  ASSERT_GT(pcd.size(), 8192u);
  const auto form =
      client->Post("/api/scenes?name=form.pcd", pcd, "application/x-www-form-urlencoded");
  ASSERT_TRUE(form);
  EXPECT_EQ(form->status, 201) << form->body;
  const auto untyped = client->Post("/api/scenes?name=untyped.pcd", pcd, "");
  ASSERT_TRUE(untyped);
  EXPECT_EQ(untyped->status, 201) << untyped->body;
  // An HTML form's upload: the content of its one file, named by it.
  const httplib::MultipartFormDataItems items = {
      {"note", "a text field", "", ""}, {"file", pcd, "multipart.pcd", "application/octet-stream"}};
  const auto multipart = client->Post("/api/scenes", items);
  ASSERT_TRUE(multipart);
  EXPECT_EQ(multipart->status, 201) << multipart->body;
  const httplib::MultipartFormDataItems two = {{"a", pcd, "a.pcd", ""}, {"b", pcd, "b.pcd", ""}};
  const auto both = client->Post("/api/scenes", two);
  ASSERT_TRUE(both);
  EXPECT_EQ(both->status, 400);
  EXPECT_NE(both->body.find("more than one file"), std::string::npos) << both->body;

  // The command of docs/serve.md itself, with the token header it shows.
  if (std::system("command -v curl >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "curl is not installed (scripts/install-deps.sh installs it)";
  }
  const std::string out = dir.file("curl.out");
  const std::string command =
      "curl -s -o '" + out + "' -w '%{http_code}' -H 'Authorization: token " + server->token() +
      "' -X POST 'localhost:" + std::to_string(port) +
      "/api/scenes?name=new.pcd' --data-binary @'" + scene_file + "' > '" + out + ".status'";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  EXPECT_EQ(read_bytes(out + ".status"), "201") << read_bytes(out);
  const Reply scenes = get("/api/scenes");
  EXPECT_NE(scenes.text.find("new.pcd"), std::string::npos) << scenes.text;
}

// Issue #34, finding 5: a byte that is not UTF-8 gave 500 and a body that was not JSON; a NUL cut
// the message short; "-rf.lmk" was written; a program id was called a "landmark name".
TEST_F(ServeTest, HostileNamesAreRefusedWithValidJsonThatShowsThem) {
  start();
  for (const std::string path :
       {"/api/scenes/%ff", "/api/landmarks/%c3%28", "/api/jobs/%ed%a0%80", "/api/info?x=%ff"}) {
    const Reply r = get(path);
    EXPECT_EQ(r.status, 400) << path << ": " << r.text;
    ASSERT_FALSE(r.body.is_null()) << path << ": not JSON: " << r.text;
    EXPECT_NE(r.body["error"].get<std::string>().find("not valid UTF-8"), std::string::npos);
  }
  const Reply upload = post_bytes("/api/scenes?name=%ff.pcd", "x");
  EXPECT_EQ(upload.status, 400) << upload.text;
  EXPECT_FALSE(upload.body.is_null()) << upload.text;
  // A JSON body with a string that is not UTF-8: the parser's reason, as JSON.
  const Reply body = post_text("/api/guess", "{\"scene\": \"\xff\"}");
  EXPECT_EQ(body.status, 400) << body.text;
  EXPECT_FALSE(body.body.is_null()) << body.text;

  const Reply nul = post(
      "/api/landmarks",
      {{"scene", "1"}, {"name", std::string("milk\0evil", 9)}, {"box", box_json(carton_box())}});
  EXPECT_EQ(nul.status, 400);
  EXPECT_NE(nul.text.find("milk\\\\x00evil"), std::string::npos) << nul.text;  // all of it
  const Reply dash =
      post("/api/landmarks", {{"scene", "1"}, {"name", "-rf"}, {"box", box_json(carton_box())}});
  EXPECT_EQ(dash.status, 400) << dash.text;
  EXPECT_NE(dash.text.find("not starting with '.' or '-'"), std::string::npos) << dash.text;
  EXPECT_FALSE(fs::exists(fs::path(landmarks_dir) / "-rf.lmk"));
  EXPECT_EQ(post_bytes("/api/scenes?name=-rf.pcd", read_bytes(scene_file)).status, 400);
  const Reply program = get("/api/programs/-x");
  EXPECT_EQ(program.status, 400);
  EXPECT_NE(program.text.find("program id '-x'"), std::string::npos) << program.text;
  // Issue #34, finding 3: max_points=5000000 took 1.08 GB and 11 s.
  const Reply huge = get("/api/scenes/1/cloud?max_points=5000000");
  EXPECT_EQ(huge.status, 400) << huge.text.substr(0, 200);
  EXPECT_NE(huge.text.find("[1, 2000000]"), std::string::npos) << huge.text.substr(0, 200);
  EXPECT_EQ(get("/api/scenes/1/cloud?max_points=2000000").status, 200);
  const Reply string_box = post("/api/check", {{"scene", "1"}, {"box", "big"}});
  EXPECT_EQ(string_box.status, 400);
  EXPECT_NE(string_box.text.find("box: must be a box"), std::string::npos) << string_box.text;
  EXPECT_NE(string_box.text.find("not a string"), std::string::npos) << string_box.text;
  EXPECT_EQ(get("/api/info").status, 200);
}

// Issue #34, finding 5: a crashed server left its scratch directory in /tmp for good. The next
// server removes those of servers that are gone, and no other.
TEST_F(ServeTest, TheScratchDirectoriesOfDeadServersGoAtStart) {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  ::waitpid(child, nullptr, 0);  // a process id that has ended
  const fs::path temp = fs::temp_directory_path();
  const fs::path stale = temp / ("lmk-serve-" + std::to_string(child) + "-test01");
  const fs::path live = temp / ("lmk-serve-" + std::to_string(::getpid()) + "-test02");
  const fs::path other = temp / "lmk-serve-notapid-test03";
  for (const fs::path& d : {stale, live, other}) {
    fs::create_directories(d);
    write_text((d / "upload-1.pcd").string(), "x");
  }
  start();
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(live / "upload-1.pcd"));
  EXPECT_TRUE(fs::exists(other / "upload-1.pcd"));
  for (const fs::path& d : {live, other}) fs::remove_all(d);
}

// Issue #34, finding 3: a 50-million-point upload kept 590 MB resident, and 16 were kept.
TEST_F(ServeTest, UploadsAreBoundedInPointsEachAndInPointsKept) {
  serve::ServeSettings settings;
  const std::string pcd = read_bytes(scene_file);
  const std::size_t points = read_cloud(scene_file).size();
  settings.max_upload_points = points - 1;
  start(settings);
  const Reply big = post_bytes("/api/scenes?name=big.pcd", pcd);
  EXPECT_EQ(big.status, 413) << big.text;
  EXPECT_NE(big.text.find("points; at most " + std::to_string(points - 1) + " per upload"),
            std::string::npos)
      << big.text;
  TearDown();

  settings = serve::ServeSettings();
  settings.max_uploaded_points = 2 * points;  // room for two uploads of this frame
  start(settings);
  for (const char* name : {"one.pcd", "two.pcd", "three.pcd"}) {
    EXPECT_EQ(post_bytes(std::string("/api/scenes?name=") + name, pcd).status, 201) << name;
  }
  std::vector<std::string> kept;
  const Reply scenes = get("/api/scenes");
  for (const auto& s : scenes.body["scenes"]) {
    if (s["source"] == "upload") kept.push_back(s["name"]);
  }
  EXPECT_EQ(kept, (std::vector<std::string>{"two.pcd", "three.pcd"}));  // the oldest went
}

TEST_F(ServeTest, NoBadRequestStopsTheServer) {
  start();
  const std::vector<std::pair<std::string, std::string>> bodies = {
      {"/api/guess", ""},
      {"/api/guess", "null"},
      {"/api/guess", "{\"scene\": 1, \"point\": [1, 2, 3]}"},
      {"/api/guess", "{\"scene\": \"1\", \"point\": [1e400, 0, 0]}"},
      {"/api/guess", "{\"scene\": \"1\", \"point\": [\"a\", 0, 0]}"},
      {"/api/check", "{\"scene\": \"1\", \"box\": 5}"},
      {"/api/landmarks", "{\"scene\": \"1\", \"name\": 7}"},
      {"/api/find", "{\"scene\": \"1\", \"landmarks\": [1, 2]}"},
      {"/api/find", std::string(100000, '[')},
      {"/api/programs/x/plan", "{}"},
      // Issue #34, finding 2: these crashed the server inside oneTBB or held it at 4.8 GB.
      {"/api/find",
       "{\"scene\": \"1\", \"landmarks\": [\"carton\"], \"settings\": {\"execution\": "
       "{\"threads\": 2000000000}}}"},
      {"/api/find",
       "{\"scene\": \"1\", \"landmarks\": [\"carton\"], \"settings\": {\"scene\": {\"field_band\": "
       "1e308}}}"},
      {"/api/guess", "{\"scene\": \"1\", \"point\": [0, 0, 1], \"margin\": 1e9}"},
  };
  for (const auto& [path, body] : bodies) {
    const Reply r = post_text(path, body);
    EXPECT_GE(r.status, 400) << path << " " << body.substr(0, 60) << ": " << r.text;
    EXPECT_LT(r.status, 500) << path << " " << body.substr(0, 60) << ": " << r.text;
    EXPECT_TRUE(r.body.contains("error")) << r.text;
  }
  EXPECT_EQ(get("/api/info").status, 200);
}

}  // namespace
}  // namespace lmk::test
