// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/serve/connection_limits.h"

#include <algorithm>

namespace lmk::serve {
namespace {

ConnectionTable::Clock::rep ticks_after(double seconds) {
  const auto after =
      ConnectionTable::Clock::now() + std::chrono::duration_cast<ConnectionTable::Clock::duration>(
                                          std::chrono::duration<double>(seconds));
  return after.time_since_epoch().count();
}

}  // namespace

ConnectionTable::ConnectionTable(ConnectionLimits limits) : limits_(limits) {}

std::shared_ptr<ConnectionTable::Connection> ConnectionTable::open(const std::string& address) {
  auto connection = std::make_shared<Connection>();
  connection->address = address;
  connection->deadline = ticks_after(limits_.header_seconds);
  const std::lock_guard<std::mutex> lock(mutex_);
  connection->order = next_order_++;
  std::size_t waiting = 0;
  Connection* oldest = nullptr;
  const auto [begin, end] = by_address_.equal_range(address);
  for (auto it = begin; it != end; ++it) {
    Connection& c = *it->second;
    if (!c.waiting_for_headers || c.cut_off) continue;
    ++waiting;
    if (oldest == nullptr || c.order < oldest->order) oldest = &c;
  }
  if (oldest != nullptr && waiting >= limits_.slow_per_client) {
    oldest->cut_off = true;
    ++cut_off_;
  }
  by_address_.emplace(address, connection);
  return connection;
}

void ConnectionTable::close(const std::shared_ptr<Connection>& connection) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto [begin, end] = by_address_.equal_range(connection->address);
  for (auto it = begin; it != end; ++it) {
    if (it->second == connection) {
      // Cut off by its deadline rather than by a newer connection: counted here, once.
      if (!connection->cut_off && Clock::now() >= connection->deadline_time()) ++cut_off_;
      by_address_.erase(it);
      return;
    }
  }
}

void ConnectionTable::awaiting_request(Connection& connection) {
  const std::lock_guard<std::mutex> lock(mutex_);
  connection.waiting_for_headers = true;
  connection.deadline = ticks_after(limits_.header_seconds);
}

void ConnectionTable::headers_read(Connection& connection, std::size_t body_bytes) {
  const std::lock_guard<std::mutex> lock(mutex_);
  connection.waiting_for_headers = false;
  connection.deadline = ticks_after(limits_.header_seconds + static_cast<double>(body_bytes) /
                                                                 limits_.body_bytes_per_second);
}

std::size_t ConnectionTable::open_connections() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return by_address_.size();
}

std::size_t ConnectionTable::cut_off_connections() const { return cut_off_.load(); }

ConnectionTable::Connection*& ConnectionTable::current() {
  thread_local Connection* connection = nullptr;
  return connection;
}

}  // namespace lmk::serve
