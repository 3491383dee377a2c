// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/serve/connection_limits.h"

#include <algorithm>
#include <map>
#include <vector>

namespace lmk::serve {
namespace {

// How often the limits on waiting connections are enforced, at most.
constexpr auto kEnforceEvery = std::chrono::milliseconds(50);

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
  connection->waiting_since = Clock::now();
  connection->deadline = ticks_after(limits_.header_seconds);
  const std::lock_guard<std::mutex> lock(mutex_);
  connection->order = next_order_++;
  by_address_.emplace(address, connection);
  enforce_locked();
  return connection;
}

void ConnectionTable::enforce() {
  // At most every 50 ms, whoever calls: every waiting thread looks in once a slice.
  const Clock::rep now = Clock::now().time_since_epoch().count();
  const Clock::rep every = std::chrono::duration_cast<Clock::duration>(kEnforceEvery).count();
  Clock::rep last = last_enforced_.load();
  if (now - last < every || !last_enforced_.compare_exchange_strong(last, now)) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  enforce_locked();
}

void ConnectionTable::enforce_locked() {
  const Clock::time_point now = Clock::now();
  const auto young = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(limits_.young_seconds));
  std::vector<Connection*> waiting;
  std::map<std::string, std::size_t> per_address;
  for (const auto& [from, c] : by_address_) {
    if (!c->waiting_for_headers || c->authenticated || c->cut_off) continue;
    waiting.push_back(c.get());
    ++per_address[from];
  }
  std::sort(waiting.begin(), waiting.end(),
            [](const Connection* a, const Connection* b) { return a->order < b->order; });
  std::size_t total = waiting.size();
  for (Connection* c : waiting) {
    std::size_t& mine = per_address[c->address];
    if (mine <= limits_.slow_per_client && total <= limits_.unauthenticated_total) continue;
    if (now - c->waiting_since < young) continue;  // too young to judge
    c->cut_off = true;
    ++cut_off_;
    --mine;
    --total;
  }
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

void ConnectionTable::awaiting_request(Connection& connection) {
  const std::lock_guard<std::mutex> lock(mutex_);
  connection.waiting_for_headers = true;
  connection.waiting_since = Clock::now();
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
