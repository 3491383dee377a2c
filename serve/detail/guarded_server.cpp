// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/serve/detail/guarded_server.h"

#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

namespace lmk::serve::detail {
namespace {

using Clock = ConnectionTable::Clock;

// How often a waiting read looks at its connection's deadline and the server's state.
constexpr auto kSlice = std::chrono::milliseconds(100);

// The numeric address and port of one end of `sock`, as httplib reports them to handlers.
void endpoint(int sock, bool peer, std::string& address, int& port) {
  sockaddr_storage storage{};
  socklen_t length = sizeof storage;
  auto* where = reinterpret_cast<sockaddr*>(&storage);
  const int got = peer ? ::getpeername(sock, where, &length) : ::getsockname(sock, where, &length);
  char host[NI_MAXHOST] = "", service[NI_MAXSERV] = "0";
  if (got != 0 || ::getnameinfo(where, length, host, sizeof host, service, sizeof service,
                                NI_NUMERICHOST | NI_NUMERICSERV) != 0) {
    address.clear();
    port = 0;
    return;
  }
  address = host;
  port = std::atoi(service);
}

// A connection's socket as httplib's Stream: every wait for bytes is cut into slices, and ends
// at the connection's deadline, when it is cut off, or after `timeout` without a byte.
class DeadlineStream : public httplib::Stream {
 public:
  DeadlineStream(int sock, ConnectionTable& table, const ConnectionTable::Connection& connection,
                 std::chrono::microseconds read_timeout, std::chrono::microseconds write_timeout)
      : sock_(sock),
        table_(table),
        connection_(connection),
        read_timeout_(read_timeout),
        write_timeout_(write_timeout) {}

  bool is_readable() const override { return wait(POLLIN, read_timeout_, true); }
  bool is_writable() const override { return wait(POLLOUT, write_timeout_, false); }

  ssize_t read(char* ptr, size_t size) override {
    if (!wait(POLLIN, read_timeout_, true)) return -1;
    ssize_t n;
    do {
      n = ::recv(sock_, ptr, size, 0);
    } while (n < 0 && errno == EINTR);
    return n;
  }

  ssize_t write(const char* ptr, size_t size) override {
    if (!wait(POLLOUT, write_timeout_, false)) return -1;
    ssize_t n;
    do {
      n = ::send(sock_, ptr, size, MSG_NOSIGNAL);
    } while (n < 0 && errno == EINTR);
    return n;
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    endpoint(sock_, true, ip, port);
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    endpoint(sock_, false, ip, port);
  }
  socket_t socket() const override { return sock_; }

  /// Waits up to `timeout` for `events`; a wait to read also ends at the connection's deadline,
  /// and enforces the limits on waiting connections as they come of age.
  bool wait(short events, std::chrono::microseconds timeout, bool reading) const {
    const Clock::time_point give_up = Clock::now() + timeout;
    while (true) {
      if (reading) table_.enforce();
      if (reading && connection_.expired()) return false;
      const Clock::time_point now = Clock::now();
      if (now >= give_up) return false;
      Clock::time_point until = std::min(give_up, now + kSlice);
      if (reading) until = std::min(until, connection_.deadline_time());
      const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(until - now).count();
      pollfd p{sock_, events, 0};
      const int ready = ::poll(&p, 1, static_cast<int>(std::max<long long>(ms, 1)));
      if (ready > 0) return true;
      if (ready < 0 && errno != EINTR) return false;
    }
  }

 private:
  int sock_;
  ConnectionTable& table_;
  const ConnectionTable::Connection& connection_;
  std::chrono::microseconds read_timeout_, write_timeout_;
};

std::chrono::microseconds microseconds(time_t seconds, time_t useconds) {
  return std::chrono::seconds(seconds) + std::chrono::microseconds(useconds);
}

}  // namespace

bool GuardedServer::process_and_close_socket(socket_t sock) {
  std::string address;
  int port = 0;
  endpoint(sock, true, address, port);
  const std::shared_ptr<ConnectionTable::Connection> connection = table_.open(address);
  DeadlineStream stream(sock, table_, *connection,
                        microseconds(read_timeout_sec_, read_timeout_usec_),
                        microseconds(write_timeout_sec_, write_timeout_usec_));
  bool ok = false;
  // As httplib's own loop: up to keep_alive_max_count_ requests, each awaited for at most the
  // keep-alive timeout, while the server runs.
  for (std::size_t left = keep_alive_max_count_; left > 0 && svr_sock_ != INVALID_SOCKET; --left) {
    table_.awaiting_request(*connection);
    bool arrived = false;
    const Clock::time_point idle_until =
        Clock::now() + std::chrono::seconds(keep_alive_timeout_sec_);
    while (!arrived && svr_sock_ != INVALID_SOCKET && Clock::now() < idle_until &&
           !connection->expired()) {
      arrived =
          stream.wait(POLLIN, std::chrono::duration_cast<std::chrono::microseconds>(kSlice), true);
    }
    if (!arrived) break;
    bool closed = false;
    ConnectionTable::current() = connection.get();
    ok = process_request(stream, left == 1, closed, nullptr);
    ConnectionTable::current() = nullptr;
    // A request cut short by its deadline is answered 400 by httplib, which then waits for the
    // next on the same connection: the connection ends here instead.
    if (!ok || closed || connection->expired()) break;
  }
  table_.close(connection);
  ::shutdown(sock, SHUT_RDWR);
  ::close(sock);
  return ok;
}

}  // namespace lmk::serve::detail
