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

std::shared_ptr<ConnectionTable::Connection> ConnectionTable::open(const std::string& address,
                                                                   bool sending) {
  auto connection = std::make_shared<Connection>();
  connection->address = address;
  connection->idle = !sending;
  connection->deadline = ticks_after(limits_.header_seconds);
  const std::lock_guard<std::mutex> lock(mutex_);
  connection->order = next_order_++;
  // The first to cut among the waiting connections that have not shown the token, of this
  // address and of anyone: the oldest idle one, else the oldest. With how many wait of each.
  std::size_t mine = 0, everyone = 0;
  Connection *my_first = nullptr, *first = nullptr;
  const auto before = [](const Connection* a, const Connection* b) {
    return b == nullptr || (a->idle != b->idle ? a->idle : a->order < b->order);
  };
  for (const auto& [from, c] : by_address_) {
    if (!c->waiting_for_headers || c->authenticated || c->cut_off) continue;
    ++everyone;
    if (before(c.get(), first)) first = c.get();
    if (from != address) continue;
    ++mine;
    if (before(c.get(), my_first)) my_first = c.get();
  }
  const auto cut = [this](Connection* c) {
    if (c == nullptr || c->cut_off) return;
    c->cut_off = true;
    ++cut_off_;
  };
  if (mine >= limits_.slow_per_client) cut(my_first);
  if (everyone >= limits_.unauthenticated_total) cut(first);
  by_address_.emplace(address, connection);
  return connection;
}

void ConnectionTable::bytes_arrived(Connection& connection) {
  const std::lock_guard<std::mutex> lock(mutex_);
  connection.idle = false;
}

void ConnectionTable::authenticated(Connection& connection) {
  const std::lock_guard<std::mutex> lock(mutex_);
  connection.authenticated = true;
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

void ConnectionTable::awaiting_request(Connection& connection, bool sending) {
  const std::lock_guard<std::mutex> lock(mutex_);
  connection.waiting_for_headers = true;
  connection.idle = !sending;
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
