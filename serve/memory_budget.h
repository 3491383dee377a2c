// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The memory `lmk serve` lets its work take (issue #47): every upload, every kept scene and every
// job reserves its estimated peak before it starts, and is refused with 503 and Retry-After when
// that does not fit what is left. Two searches on an uploaded 5-million-point scene had peaked at
// 3.3 GB; with a budget the server's memory is the budget plus what the process needs to run.
#include <cstddef>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

namespace lmk::serve {

/// Half the memory this machine (or its cgroup, when that is less) has: what `lmk serve` takes
/// without --memory-budget.
std::size_t default_memory_budget();

/// What reading and parsing a JSON request body of `bytes` holds: the text, and its parse, which
/// grows it about 20-fold (a number of two characters becomes a 16-byte value in a vector).
/// Reserved from the request's headers until its handler has answered.
inline std::size_t json_body_price(std::size_t bytes) { return 21 * bytes; }

class MemoryBudget {
 public:
  explicit MemoryBudget(std::size_t bytes);

  /// Bytes held for one piece of work until it is destroyed (or released). Move-only.
  class Reservation {
   public:
    Reservation() = default;
    ~Reservation() { release(); }
    Reservation(Reservation&& other) noexcept;
    Reservation& operator=(Reservation&& other) noexcept;
    Reservation(const Reservation&) = delete;
    Reservation& operator=(const Reservation&) = delete;

    std::size_t bytes() const { return bytes_; }
    /// Keeps `bytes` from now, never more than reserved: what an upload keeps once it is parsed.
    void shrink_to(std::size_t bytes);
    void release();

   private:
    friend class MemoryBudget;
    struct State;
    Reservation(std::shared_ptr<State> state, std::size_t bytes, const char* kind)
        : state_(std::move(state)), bytes_(bytes), kind_(kind) {}
    std::shared_ptr<State> state_;
    std::size_t bytes_ = 0;
    const char* kind_ = "";
  };

  /// Reserves `bytes` for work of `kind` ("upload", "scene", "find", ...), described to the client
  /// as `what`. ApiError 503 with Retry-After when it does not fit what is left now; 413 when it
  /// is more than the whole budget, which no wait would change.
  Reservation reserve(std::size_t bytes, const char* kind, const std::string& what);
  /// Reserves `bytes` whatever is left (the scenes the server was started with): they are in
  /// memory already.
  Reservation reserve_anyway(std::size_t bytes, const char* kind);

  std::size_t budget() const;
  std::size_t in_use() const;
  /// {budget, in_use, by_kind: {kind: bytes}, refused}: for /api/info.
  nlohmann::json to_json() const;

 private:
  std::shared_ptr<Reservation::State> state_;
};

}  // namespace lmk::serve
