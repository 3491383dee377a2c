// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// An API request that cannot be served, with its HTTP status: the server answers
// {"error": message} with that status and keeps running.
#include <stdexcept>
#include <string>

namespace lmk::serve {

class ApiError : public std::runtime_error {
 public:
  ApiError(int status, const std::string& message) : std::runtime_error(message), status_(status) {}
  int status() const { return status_; }

 private:
  int status_;
};

inline ApiError bad_request(const std::string& m) { return ApiError(400, m); }
inline ApiError forbidden(const std::string& m) { return ApiError(403, m); }
inline ApiError not_found(const std::string& m) { return ApiError(404, m); }
inline ApiError conflict(const std::string& m) { return ApiError(409, m); }

}  // namespace lmk::serve
