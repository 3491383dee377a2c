// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Connections that cannot hold `lmk serve` (issue #47; docs/serve.md, "Safety"). Every connection
// holds one of the server's HTTP threads while it is open, so a client that sends its headers a
// line every few seconds could hold them all. Here each connection has a deadline: its request's
// headers must have arrived within `header_seconds` of the server waiting for them, and its body
// at least at `body_bytes_per_second` on average after that grace. And one address keeps at most
// `slow_per_client` connections waiting for their headers at once: a further one cuts off its
// oldest, so that a flood of slow connections from one client leaves the other threads to the
// page, the API and the other clients.
//
// A connection that has shown the token is a client's (issue #61, finding 6): the limits on
// waiting connections count only those that have not, and never cut off one that has, even while
// it waits for its next request. 200-300 idle connections from the same address cut off the
// keep-alive connections of the client that had the token. All addresses together keep at most
// `unauthenticated_total` such connections waiting, so that the other threads stay free for
// requests that show the token. And a connection is judged only once it has waited
// `young_seconds`: a client sends its headers at once, but the thread that took its connection
// may not run at once on a busy machine, and a flood of idle connections cut off such clients
// while they were the oldest waiting.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace lmk::serve {

struct ConnectionLimits {
  /// s from waiting for a request to the end of its headers: a browser or curl sends them at once.
  double header_seconds = 10.0;
  /// The least average rate of a body after the headers' grace, bytes/s (1 MiB/s: a 256 MiB
  /// upload may take 4 minutes).
  double body_bytes_per_second = 1024.0 * 1024.0;
  /// Connections of one address that may wait for their headers at once without having shown
  /// the token (a browser opens 6).
  std::size_t slow_per_client = 16;
  /// Connections of all addresses that may wait for their headers at once without having shown
  /// the token: half the server's 64 HTTP threads.
  std::size_t unauthenticated_total = 32;
  /// s a connection waits for its headers before the limits above may cut it off.
  double young_seconds = 0.25;
};

class ConnectionTable {
 public:
  using Clock = std::chrono::steady_clock;

  /// One open connection. The thread serving it reads `deadline` and `cut_off` before every wait.
  struct Connection {
    std::string address;  ///< the client's numeric address
    std::uint64_t order = 0;
    bool waiting_for_headers = true;  ///< guarded by the table's lock
    bool authenticated = false;       ///< a request on it showed the token; guarded likewise
    Clock::time_point waiting_since;  ///< when it began to wait for headers; guarded likewise
    std::atomic<Clock::rep> deadline{0};
    std::atomic<bool> cut_off{false};

    Clock::time_point deadline_time() const {
      return Clock::time_point(Clock::duration(deadline.load()));
    }
    /// Whether reading must stop: cut off, or past its deadline.
    bool expired() const { return cut_off.load() || Clock::now() >= deadline_time(); }
  };

  explicit ConnectionTable(ConnectionLimits limits = {});

  /// A connection from `address`, waiting for its first request (then enforce()).
  std::shared_ptr<Connection> open(const std::string& address);
  /// A request on the connection showed the token: no limit on waiting connections cuts it off.
  void authenticated(Connection& connection);
  /// Cuts off, oldest first, the connections waiting for their headers without having shown the
  /// token beyond slow_per_client of one address or unauthenticated_total in all, among those
  /// that have waited young_seconds. Called as connections open, and by the threads that wait
  /// for them (at most every 50 ms), so that a flood is cut as its connections come of age.
  void enforce();
  void close(const std::shared_ptr<Connection>& connection);
  /// The server waits for the connection's next request: its headers are due within
  /// header_seconds.
  void awaiting_request(Connection& connection);
  /// Its headers arrived, announcing `body_bytes` to come (0: none): the body is due at the
  /// least rate after the grace.
  void headers_read(Connection& connection, std::size_t body_bytes);

  std::size_t open_connections() const;
  /// Connections cut off so far, by deadline or by a newer one of the same client.
  std::size_t cut_off_connections() const;

  /// The connection the calling thread serves, or null: the request handlers run on the thread
  /// that read the request.
  static Connection*& current();

 private:
  ConnectionLimits limits_;
  mutable std::mutex mutex_;
  std::uint64_t next_order_ = 0;
  std::multimap<std::string, std::shared_ptr<Connection>> by_address_;
  std::atomic<std::size_t> cut_off_{0};
  std::atomic<Clock::rep> last_enforced_{0};
  void enforce_locked();
};

}  // namespace lmk::serve
