// SPDX-License-Identifier: BSD-3-Clause
#include "tests/serve/serve_fixture.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <filesystem>

#include "lmk/geometry/cloud_io.h"
#include "lmk/json/settings_json.h"
#include "lmk/pbd/program.h"
#include "lmk/sim/depth_sensor.h"

namespace lmk::test {

void ServeTest::SetUp() {
  tabletop = make_tabletop_scene(1);
  // The frame `lmk gen --seed 1` writes (scripts/tabletop-demo.sh captures its carton).
  DepthSensorSettings sensor;
  sensor.seed = 1;
  const PointCloud cloud = render_depth(tabletop.mesh, tabletop.T_world_sensor, sensor);
  scene_file = dir.file("tabletop.pcd");
  write_cloud(scene_file, cloud);
  // The same frame 0.9 m further along x: the table in front of a PR2 standing at the origin.
  robot_scene_file = dir.file("tabletop_in_front.pcd");
  write_cloud(robot_scene_file,
              cloud.transformed(Eigen::Isometry3d(Eigen::Translation3d(0.9, 0.0, 0.0))));
  landmarks_dir = dir.file("landmarks");
  programs_dir = dir.file("programs");
  std::filesystem::create_directories(programs_dir);
}

void ServeTest::TearDown() {
  client.reset();
  if (server) server->stop();
  if (thread.joinable()) thread.join();
  server.reset();
}

void ServeTest::start(serve::ServeSettings settings, std::ostream* log) {
  if (settings.scenes.empty()) settings.scenes = {scene_file, robot_scene_file};
  if (settings.landmarks_dir == serve::ServeSettings().landmarks_dir) {
    settings.landmarks_dir = landmarks_dir;
  }
  if (settings.programs_dir.empty()) settings.programs_dir = programs_dir;
  settings.port = 0;
  settings.base_frame = true;
  server = std::make_unique<serve::HttpServer>(settings, log);
  port = server->bind();
  thread = std::thread([this] { server->run(); });
  client = new_client();
  // run() is listening once a request is answered.
  for (int i = 0; i < 200 && !client->Get("/api/info"); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

std::unique_ptr<httplib::Client> ServeTest::new_client() const {
  auto c = std::make_unique<httplib::Client>("127.0.0.1", port);
  c->set_read_timeout(std::chrono::seconds(300));
  c->set_default_headers({{"Authorization", "token " + server->token()}});
  return c;
}

Reply reply_of(const httplib::Result& r) {
  Reply out;
  if (!r) {
    out.status = -1;
    out.text = "no response: " + httplib::to_string(r.error());
    return out;
  }
  out.status = r->status;
  out.text = r->body;
  out.body = nlohmann::json::parse(r->body, nullptr, false);
  if (out.body.is_discarded()) out.body = nullptr;
  return out;
}

Reply ServeTest::get(const std::string& path) { return reply_of(client->Get(path.c_str())); }

Reply ServeTest::post(const std::string& path, const nlohmann::json& body) {
  return reply_of(client->Post(path.c_str(), body.dump(), "application/json"));
}

Reply ServeTest::post_bytes(const std::string& path, const std::string& bytes) {
  return reply_of(client->Post(path.c_str(), bytes, "application/octet-stream"));
}

Reply ServeTest::post_text(const std::string& path, const std::string& text) {
  return reply_of(client->Post(path.c_str(), text, "application/json"));
}

Reply ServeTest::until_finished(httplib::Client& c, Reply r) {
  // A job still running after the server's longest wait (kMaxRequestWait) is answered 202: poll.
  if (r.status != 202 || !r.body.contains("job")) return r;
  const std::string url = "/api/jobs/" + r.body["job"].get<std::string>() + "?wait=10";
  while (r.status == 202) {
    r = reply_of(c.Get(url.c_str()));
    if (r.status == 200 && r.body.value("state", "") == "failed") {
      r.status = r.body.value("status", 500);
    } else if (r.status == 200 && r.body.value("state", "") != "done") {
      r.status = 202;  // still queued or running
    }
  }
  return r;
}

nlohmann::json ServeTest::run(const std::string& path, nlohmann::json body) {
  body["wait"] = true;
  const Reply r = until_finished(*client, post(path, body));
  EXPECT_EQ(r.status, 200) << path << ": " << r.text;
  EXPECT_EQ(r.body.value("state", ""), "done") << r.text;
  return r.body.value("result", nlohmann::json());
}

Box ServeTest::carton_box() const {
  for (const SceneObject& o : tabletop.objects) {
    if (o.name == "carton") {
      // As scripts/tabletop-demo.sh draws it: 2 cm of free space around and above it, and its
      // bottom 1 mm into the table top. Seen nearly face-on from this camera, the carton alone is
      // a flat face; the sliver of table gives it the relief capture requires.
      return Box(o.box.pose * Eigen::Translation3d(0.0, 0.0, 0.011),
                 o.box.size + Eigen::Vector3d(0.04, 0.04, 0.02));
    }
  }
  ADD_FAILURE() << "the tabletop has no carton";
  return {};
}

void ServeTest::capture_carton() {
  const Reply r =
      post("/api/landmarks", {{"scene", "1"}, {"name", "carton"}, {"box", box_json(carton_box())}});
  ASSERT_EQ(r.status, 201) << r.text;
}

FindSettings ServeTest::scene_settings() {
  FindSettings s;
  s.scene.base_frame = true;
  return s;
}

RawConnection::RawConnection(int port) : sock_(::socket(AF_INET, SOCK_STREAM, 0)) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  connected_ = ::connect(sock_, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
}

RawConnection::~RawConnection() { ::close(sock_); }

bool RawConnection::send(const std::string& bytes) {
  return ::send(sock_, bytes.data(), bytes.size(), MSG_NOSIGNAL) ==
         static_cast<ssize_t>(bytes.size());
}

std::string RawConnection::read_to_end() {
  std::string out;
  char buffer[4096];
  for (ssize_t n; (n = ::recv(sock_, buffer, sizeof buffer, 0)) > 0;) out.append(buffer, n);
  return out;
}

bool RawConnection::closed_by_server() const {
  pollfd p{sock_, POLLIN, 0};
  if (::poll(&p, 1, 0) <= 0) return false;
  char byte = 0;
  const ssize_t n = ::recv(sock_, &byte, 1, MSG_PEEK | MSG_DONTWAIT);
  return n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK);
}

nlohmann::json box_json(const Box& box) { return detail::setting_to_json(box); }

nlohmann::json without_times(nlohmann::json j) {
  if (j.is_object()) {
    nlohmann::json out = nlohmann::json::object();
    for (auto& item : j.items()) {
      if (item.key().rfind("seconds", 0) == 0) continue;
      out[item.key()] = without_times(item.value());
    }
    return out;
  }
  if (j.is_array()) {
    for (auto& x : j) x = without_times(x);
  }
  return j;
}

}  // namespace lmk::test
