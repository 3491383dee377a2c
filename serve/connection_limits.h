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
  /// Connections of one address that may wait for their headers at once (a browser opens 6).
  std::size_t slow_per_client = 16;
};

class ConnectionTable {
 public:
  using Clock = std::chrono::steady_clock;

  /// One open connection. The thread serving it reads `deadline` and `cut_off` before every wait.
  struct Connection {
    std::string address;  ///< the client's numeric address
    std::uint64_t order = 0;
    bool waiting_for_headers = true;  ///< guarded by the table's lock
    std::atomic<Clock::rep> deadline{0};
    std::atomic<bool> cut_off{false};

    Clock::time_point deadline_time() const {
      return Clock::time_point(Clock::duration(deadline.load()));
    }
    /// Whether reading must stop: cut off, or past its deadline.
    bool expired() const { return cut_off.load() || Clock::now() >= deadline_time(); }
  };

  explicit ConnectionTable(ConnectionLimits limits = {});

  /// A connection from `address`, waiting for its first request; cuts off the address's oldest
  /// connection waiting for headers when it has slow_per_client of them already.
  std::shared_ptr<Connection> open(const std::string& address);
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
};

}  // namespace lmk::serve
