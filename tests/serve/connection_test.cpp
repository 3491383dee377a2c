// SPDX-License-Identifier: BSD-3-Clause
// Issue #47: connections that cannot hold `lmk serve`, and nothing a client sends reaches the
// operator's terminal raw. Slow senders are raw sockets that send a header line now and then; the
// terminal is the server's log.
#include <atomic>
#include <chrono>
#include <sstream>
#include <thread>

#include "lmk/serve/connection_limits.h"
#include "tests/serve/serve_fixture.h"

namespace lmk::test {
namespace {

using serve::ConnectionLimits;
using serve::ConnectionTable;

TEST(ConnectionTable, AClientsNewestSlowConnectionCutsOffItsOldest) {
  ConnectionLimits limits;
  limits.slow_per_client = 3;
  limits.young_seconds = 0.0;  // judged at once
  ConnectionTable table(limits);
  std::vector<std::shared_ptr<ConnectionTable::Connection>> mine;
  for (int i = 0; i < 3; ++i) mine.push_back(table.open("10.0.0.1"));
  const auto other = table.open("10.0.0.2");
  for (const auto& c : mine) EXPECT_FALSE(c->cut_off);
  // One that has sent its headers no longer counts as slow.
  table.headers_read(*mine[0], 0);
  mine.push_back(table.open("10.0.0.1"));
  for (const auto& c : mine) EXPECT_FALSE(c->cut_off);
  // Now 3 wait for headers: a fourth cuts off the oldest of them, and nobody else's.
  mine.push_back(table.open("10.0.0.1"));
  EXPECT_FALSE(mine[0]->cut_off);
  EXPECT_TRUE(mine[1]->cut_off);
  EXPECT_FALSE(mine[2]->cut_off);
  EXPECT_FALSE(other->cut_off);
  EXPECT_EQ(table.cut_off_connections(), 1u);
  EXPECT_EQ(table.open_connections(), 6u);
  for (const auto& c : mine) table.close(c);
  table.close(other);
  EXPECT_EQ(table.open_connections(), 0u);
}

// Issue #61, finding 6: a connection that showed the token is never cut off by ones that have
// not, and all addresses together keep at most unauthenticated_total of those waiting.
TEST(ConnectionTable, ConnectionsWithoutTheTokenNeverCutOffOnesWithIt) {
  ConnectionLimits limits;
  limits.slow_per_client = 3;
  limits.unauthenticated_total = 5;
  limits.young_seconds = 0.0;
  ConnectionTable table(limits);
  const auto client = table.open("127.0.0.1");
  table.headers_read(*client, 0);
  table.authenticated(*client);
  table.awaiting_request(*client);  // keep-alive: waiting for its next request
  std::vector<std::shared_ptr<ConnectionTable::Connection>> flood;
  for (int i = 0; i < 20; ++i) flood.push_back(table.open("127.0.0.1"));
  EXPECT_FALSE(client->cut_off);
  std::size_t waiting = 0;
  for (const auto& c : flood) waiting += c->cut_off ? 0 : 1;
  EXPECT_EQ(waiting, 3u);  // the address's limit
  // Others' connections: the total limit cuts the oldest of anyone's, never the client's.
  std::vector<std::shared_ptr<ConnectionTable::Connection>> others;
  for (int i = 0; i < 4; ++i) others.push_back(table.open("10.0.0." + std::to_string(i + 2)));
  waiting = 0;
  for (const auto& list : {flood, others}) {
    for (const auto& c : list) waiting += c->cut_off ? 0 : 1;
  }
  EXPECT_EQ(waiting, 5u);
  EXPECT_FALSE(client->cut_off);
  EXPECT_FALSE(others.back()->cut_off);  // the newest stays
}

// A connection is judged only once it has waited young_seconds: the thread that took a client's
// connection may not have run yet.
TEST(ConnectionTable, YoungConnectionsAreNotJudgedYet) {
  ConnectionLimits limits;
  limits.slow_per_client = 3;
  limits.young_seconds = 3600.0;
  ConnectionTable table(limits);
  std::vector<std::shared_ptr<ConnectionTable::Connection>> young;
  for (int i = 0; i < 20; ++i) young.push_back(table.open("127.0.0.1"));
  table.enforce();
  for (const auto& c : young) EXPECT_FALSE(c->cut_off);
  EXPECT_EQ(table.cut_off_connections(), 0u);
}

TEST(ConnectionTable, HeadersAreDueWithinTheirDeadlineAndABodyAtTheLeastRate) {
  ConnectionLimits limits;
  limits.header_seconds = 0.0;
  limits.body_bytes_per_second = 1.0;
  ConnectionTable table(limits);
  const auto c = table.open("10.0.0.1");
  EXPECT_TRUE(c->expired());  // no time at all for headers
  table.headers_read(*c, 3600);
  EXPECT_FALSE(c->expired());  // an hour for 3600 bytes at 1 byte/s
  table.awaiting_request(*c);
  EXPECT_TRUE(c->expired());
  table.close(c);
}

TEST_F(ServeTest, EscapeBytesInThePathReachNoTerminal) {
  std::ostringstream log;
  start({}, &log);
  // What any web page can make a browser send: clear the screen, set the title, ring the bell
  // and forge a log line.
  RawConnection c(port);
  ASSERT_TRUE(c.connected());
  ASSERT_TRUE(
      c.send("GET /api/%1b%5b2J%1b%5d0%3bX%07%0aFAKE HTTP/1.1\r\nHost: 127.0.0.1\r\n"
             "Connection: close\r\n\r\n"));
  const std::string answer = c.read_to_end();
  EXPECT_NE(answer.find("HTTP/1.1 4"), std::string::npos) << answer;
  server->stop();
  thread.join();
  const std::string text = log.str();
  ASSERT_NE(text.find("GET /api/"), std::string::npos) << text;
  for (const char ch : text) {
    const auto byte = static_cast<unsigned char>(ch);
    EXPECT_TRUE(ch == '\n' || (byte >= 0x20 && byte != 0x7f)) << "byte " << int(byte);
  }
  EXPECT_NE(text.find("\\x1b[2J\\x1b]0;X\\x07\\x0aFAKE"), std::string::npos) << text;
  EXPECT_EQ(text.find("\nFAKE"), std::string::npos) << text;  // no forged line
}

TEST_F(ServeTest, EchoedNamesAreCutAndEscaped) {
  start();
  const std::string name = "\x1b]0;pwned\x07" + std::string(100000, 'n');
  const Reply r = post("/api/check", {{"scene", name}, {"box", box_json(carton_box())}});
  EXPECT_EQ(r.status, 404) << r.text.substr(0, 300);
  const std::string error = r.body["error"];
  EXPECT_LT(error.size(), 1200u);
  EXPECT_NE(error.find("\\x1b]0;pwned\\x07nnn"), std::string::npos) << error;
  EXPECT_NE(error.find("..."), std::string::npos) << error;
}

// 100 clients that send a header line every half second, and the API still answers at once; the
// slow ones are cut off, the newest of each client first held, the rest at their deadline.
TEST_F(ServeTest, SlowSendersCannotHoldTheServer) {
  serve::ServeSettings settings;
  settings.connections.header_seconds = 3.0;
  start(settings);
  std::vector<std::unique_ptr<RawConnection>> slow;
  for (int i = 0; i < 100; ++i) {
    slow.push_back(std::make_unique<RawConnection>(port));
    ASSERT_TRUE(slow.back()->connected());
    slow.back()->send("GET /api/info HTTP/1.1\r\n");
  }
  std::atomic<bool> sending{true};
  std::thread sender([&] {
    while (sending) {
      for (auto& c : slow) c->send("X-Slow: 1\r\n");
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
  });
  // The API answers while they hold their connections: within a second, as the issue asks (it
  // answers in milliseconds; before, 20 slow senders made it time out at 60 s).
  for (int i = 0; i < 5; ++i) {
    auto c = new_client();
    const auto begin = std::chrono::steady_clock::now();
    const Reply health = reply_of(c->Get("/api/health"));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    EXPECT_EQ(health.status, 200) << health.text;
    EXPECT_LT(seconds, 1.0);
  }
  // Every slow one is cut off in the end: 84 by newer ones of the same client, the last 16 at
  // their deadline. Waited for as an event, with a cap far beyond the 3 s deadline.
  nlohmann::json connections;
  for (int i = 0; i < 300; ++i) {
    connections = get("/api/info").body["connections"];
    if (connections["cut_off"].get<std::size_t>() >= 100) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  sending = false;
  sender.join();
  EXPECT_GE(connections["cut_off"].get<std::size_t>(), 100u) << connections;
  EXPECT_EQ(get("/api/health").status, 200);
}

// Issue #61, finding 6: 300 idle connections without the token, each reopened as soon as the
// server cuts it off, while a client with the token makes requests on new and kept-alive
// connections: all 50 succeed. (Before, 12 of 78 and 20 of 58 failed.)
TEST_F(ServeTest, AFloodOfIdleConnectionsLeavesRoomForTheToken) {
  start();
  std::vector<std::unique_ptr<RawConnection>> idle;
  for (int i = 0; i < 300; ++i) idle.push_back(std::make_unique<RawConnection>(port));
  std::atomic<bool> flooding{true};
  std::atomic<std::size_t> reopened{0};
  std::thread flood([&] {
    while (flooding) {
      for (auto& c : idle) {
        if (!c->closed_by_server()) continue;
        c = std::make_unique<RawConnection>(port);
        ++reopened;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  const auto kept = new_client();
  kept->set_keep_alive(true);
  std::size_t succeeded = 0;
  for (int i = 0; i < 25; ++i) {
    const Reply fresh = reply_of(new_client()->Get("/api/info"));
    EXPECT_EQ(fresh.status, 200) << i << ": " << fresh.text;
    const Reply again = reply_of(kept->Get("/api/scenes"));
    EXPECT_EQ(again.status, 200) << i << ": " << again.text;
    succeeded += (fresh.status == 200) + (again.status == 200);
  }
  flooding = false;
  flood.join();
  EXPECT_EQ(succeeded, 50u);
  EXPECT_GT(reopened.load(), 0u);  // the flood was cut off and came back
}

}  // namespace
}  // namespace lmk::test
