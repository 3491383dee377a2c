// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Who may drive `lmk serve` (docs/serve.md, "Access"). A web page the user visits can send
// requests to 127.0.0.1 too, and a name it controls can be rebound to 127.0.0.1, so loopback alone
// proves nothing. Every request passes four checks, as Jupyter's server does:
// - Host: a loopback name, the bound address, or a name the user allowed (DNS rebinding);
// - a token, on every /api request and on the page itself: printed with the URL at start, kept by
//   the page in a cookie that browsers send only from the server's own pages;
// - Origin, on every request that changes state: absent (not a browser) or the server's own;
// - JSON only as application/json, which a cross-site page cannot send without asking first.
#include <string>
#include <string_view>
#include <vector>

namespace lmk::serve {

/// What the guard needs to know about one request; the names of HTTP's own headers.
struct RequestView {
  std::string method;         ///< "GET", "POST", ...
  std::string path;           ///< without the query
  std::string host;           ///< the Host header; empty when absent
  std::string origin;         ///< the Origin header; empty when absent
  std::string content_type;   ///< the Content-Type header; empty when absent
  std::string authorization;  ///< the Authorization header: "token T" or "Bearer T"
  std::string cookie;         ///< the Cookie header
  std::string query_token;    ///< the ?token= parameter
  bool has_query_token = false;
  bool has_body = true;  ///< false: no Content-Length above 0 and no chunked body (a bare DELETE)
};

/// The guard's answer: pass (status 0), or refuse with this status and one-line reason.
struct AccessVerdict {
  int status = 0;
  std::string error;
  /// The request carried the right token in its query: the page should keep it in the cookie.
  bool token_from_query = false;
  /// The request showed the token (or the server asks none): its connection is a client's, and
  /// no flood of connections that have not shown it may cut it off (ConnectionTable).
  bool authenticated = false;

  bool allowed() const { return status == 0; }
};

class AccessGuard {
 public:
  /// `token` empty: no token is asked (--no-token). `bind` is the address listened on;
  /// `allowed_hosts` are further names the Host header may carry (--allow-host).
  AccessGuard(std::string token, std::string bind, std::vector<std::string> allowed_hosts);

  /// The port the server listens on, which names its cookie (two servers on one machine keep
  /// their tokens apart).
  void set_port(int port);

  AccessVerdict check(const RequestView& request) const;

  /// The cookie that holds the token: "lmk_token_PORT".
  std::string cookie_name() const;
  /// The Set-Cookie value that stores the token: HttpOnly, SameSite=Strict, the whole site.
  std::string set_cookie_value() const;
  const std::string& token() const { return token_; }

 private:
  bool host_allowed(const std::string& host_header) const;
  bool token_matches(const RequestView& request, bool* from_query) const;

  std::string token_;
  std::string bind_;
  std::vector<std::string> allowed_hosts_;
  int port_ = 0;
};

/// A fresh token: 24 bytes from the system's random source, as 48 hex digits.
std::string random_token();

/// a == b, in a time that depends on their lengths only (a token compared byte by byte would tell
/// an attacker how much of a guess was right).
bool equal_in_constant_time(std::string_view a, std::string_view b);

/// The host name of a Host header, lower case, without its port or an IPv6 literal's brackets.
std::string host_name_of(std::string_view host_header);

/// Whether `address` names this machine only: localhost, 127.x.y.z or ::1.
bool is_loopback_name(const std::string& address);

}  // namespace lmk::serve
