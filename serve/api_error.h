// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// An API request that cannot be served, with its HTTP status: the server answers
// {"error": message, ...details} with that status and keeps running.
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace lmk::serve {

class ApiError : public std::runtime_error {
 public:
  /// `details`: an object whose fields the answer carries beside "error" (a refused capture's
  /// verdict), or null.
  ApiError(int status, const std::string& message, nlohmann::json details = nullptr)
      : std::runtime_error(message), status_(status), details_(std::move(details)) {}
  int status() const { return status_; }
  const nlohmann::json& details() const { return details_; }
  /// Seconds after which the client may try again (the answer's Retry-After); 0: not said.
  int retry_after() const { return retry_after_; }
  void set_retry_after(int seconds) { retry_after_ = seconds; }

 private:
  int status_;
  nlohmann::json details_;
  int retry_after_ = 0;
};

/// Seconds a client refused for want of room (the job queue full, the memory budget spent) is told
/// to wait before it tries again (Retry-After): about what a search takes.
inline constexpr int kRetryAfterSeconds = 5;

inline ApiError bad_request(const std::string& m) { return ApiError(400, m); }
inline ApiError forbidden(const std::string& m) { return ApiError(403, m); }
inline ApiError not_found(const std::string& m) { return ApiError(404, m); }
inline ApiError conflict(const std::string& m) { return ApiError(409, m); }

}  // namespace lmk::serve
