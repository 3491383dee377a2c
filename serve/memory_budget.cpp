// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/serve/memory_budget.h"

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <map>

#include "lmk/search/scene_footprint.h"
#include "lmk/serve/api_error.h"

namespace lmk::serve {
namespace {

// The cgroup's memory limit (v2, then v1), when it sets one.
std::size_t cgroup_limit() {
  for (const char* file :
       {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    std::ifstream in(file);
    unsigned long long limit = 0;
    if (in >> limit && limit > 0) return static_cast<std::size_t>(limit);
  }
  return SIZE_MAX;  // "max", or no cgroup file
}

}  // namespace

std::size_t default_memory_budget() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  const std::size_t physical =
      pages > 0 && page > 0 ? static_cast<std::size_t>(pages) * static_cast<std::size_t>(page)
                            : std::size_t{4} << 30;
  return std::min(physical, cgroup_limit()) / 2;
}

struct MemoryBudget::Reservation::State {
  explicit State(std::size_t b) : budget(b) {}
  const std::size_t budget;
  mutable std::mutex mutex;
  std::size_t in_use = 0;
  std::map<std::string, std::size_t> by_kind;
  std::size_t refused = 0;

  void give_back(const char* kind, std::size_t bytes) {
    std::lock_guard<std::mutex> lock(mutex);
    in_use -= bytes;
    by_kind[kind] -= bytes;
  }
};

MemoryBudget::Reservation::Reservation(Reservation&& other) noexcept
    : state_(std::move(other.state_)), bytes_(other.bytes_), kind_(other.kind_) {
  other.bytes_ = 0;
}

MemoryBudget::Reservation& MemoryBudget::Reservation::operator=(Reservation&& other) noexcept {
  if (this != &other) {
    release();
    state_ = std::move(other.state_);
    bytes_ = other.bytes_;
    kind_ = other.kind_;
    other.bytes_ = 0;
  }
  return *this;
}

void MemoryBudget::Reservation::shrink_to(std::size_t bytes) {
  if (!state_ || bytes >= bytes_) return;
  state_->give_back(kind_, bytes_ - bytes);
  bytes_ = bytes;
}

void MemoryBudget::Reservation::release() {
  if (state_ && bytes_ > 0) state_->give_back(kind_, bytes_);
  bytes_ = 0;
  state_.reset();
}

MemoryBudget::MemoryBudget(std::size_t bytes)
    : state_(std::make_shared<Reservation::State>(bytes)) {}

MemoryBudget::Reservation MemoryBudget::reserve(std::size_t bytes, const char* kind,
                                                const std::string& what) {
  std::lock_guard<std::mutex> lock(state_->mutex);
  if (bytes > state_->budget) {
    ++state_->refused;
    throw ApiError(413, what + " needs about " + describe_bytes(bytes) +
                            ", more than the server's whole memory budget of " +
                            describe_bytes(state_->budget) + " (lmk serve --memory-budget)");
  }
  if (state_->in_use > state_->budget || bytes > state_->budget - state_->in_use) {
    ++state_->refused;
    ApiError busy(503, what + " needs about " + describe_bytes(bytes) + "; " +
                           describe_bytes(state_->in_use) + " of the server's " +
                           describe_bytes(state_->budget) +
                           " are in use: try again when other work has finished");
    busy.set_retry_after(kRetryAfterSeconds);
    throw busy;
  }
  state_->in_use += bytes;
  state_->by_kind[kind] += bytes;
  return Reservation(state_, bytes, kind);
}

MemoryBudget::Reservation MemoryBudget::reserve_anyway(std::size_t bytes, const char* kind) {
  std::lock_guard<std::mutex> lock(state_->mutex);
  state_->in_use += bytes;
  state_->by_kind[kind] += bytes;
  return Reservation(state_, bytes, kind);
}

std::size_t MemoryBudget::budget() const { return state_->budget; }

std::size_t MemoryBudget::in_use() const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->in_use;
}

nlohmann::json MemoryBudget::to_json() const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  nlohmann::json kinds = nlohmann::json::object();
  for (const auto& [kind, bytes] : state_->by_kind) kinds[kind] = bytes;
  return {{"budget", state_->budget},
          {"in_use", state_->in_use},
          {"by_kind", kinds},
          {"refused", state_->refused}};
}

}  // namespace lmk::serve
