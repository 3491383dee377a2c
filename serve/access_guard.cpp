// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/serve/access_guard.h"

#include <algorithm>
#include <cctype>
#include <random>
#include <utility>

#include "lmk/geometry/error.h"

namespace lmk::serve {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string trim(std::string_view s) {
  const auto space = [](char c) { return c == ' ' || c == '\t'; };
  while (!s.empty() && space(s.front())) s.remove_prefix(1);
  while (!s.empty() && space(s.back())) s.remove_suffix(1);
  return std::string(s);
}

bool is_ipv4_literal(const std::string& name) {
  int dots = 0, digits = 0;
  for (const char c : name) {
    if (c == '.') {
      if (digits == 0 || digits > 3) return false;
      ++dots;
      digits = 0;
    } else if (std::isdigit(static_cast<unsigned char>(c))) {
      ++digits;
    } else {
      return false;
    }
  }
  return dots == 3 && digits > 0 && digits <= 3;
}

// A name that DNS cannot rebind: an address written out (host_name_of strips IPv6's brackets).
bool is_ip_literal(const std::string& name) {
  return is_ipv4_literal(name) || name.find(':') != std::string::npos;
}

bool is_wildcard(const std::string& bind) { return bind == "0.0.0.0" || bind == "::"; }

// The value of `name` among a Cookie header's "a=1; b=2" pairs; empty when absent.
std::string cookie_value(std::string_view header, const std::string& name) {
  while (!header.empty()) {
    const std::size_t end = std::min(header.find(';'), header.size());
    const std::string pair = trim(header.substr(0, end));
    const std::size_t eq = pair.find('=');
    if (eq != std::string::npos && pair.substr(0, eq) == name) return pair.substr(eq + 1);
    header.remove_prefix(std::min(end + 1, header.size()));
  }
  return {};
}

// The token of an "Authorization: token T" or "Authorization: Bearer T" header; empty otherwise.
std::string authorization_token(const std::string& header) {
  const std::size_t space = header.find(' ');
  if (space == std::string::npos) return {};
  const std::string scheme = lower(header.substr(0, space));
  if (scheme != "token" && scheme != "bearer") return {};
  return trim(std::string_view(header).substr(space + 1));
}

// The media type of a Content-Type header, without its parameters, lower case.
std::string media_type(const std::string& content_type) {
  return lower(trim(std::string_view(content_type).substr(0, content_type.find(';'))));
}

bool changes_state(const std::string& method) {
  return method != "GET" && method != "HEAD" && method != "OPTIONS";
}

// The one route whose body is not JSON: an uploaded cloud (POST /api/scenes).
bool takes_json(const RequestView& r) { return r.path != "/api/scenes"; }

bool needs_token(const std::string& path) { return path == "/" || path.rfind("/api/", 0) == 0; }

}  // namespace

AccessGuard::AccessGuard(std::string token, std::string bind,
                         std::vector<std::string> allowed_hosts)
    : token_(std::move(token)), bind_(lower(std::move(bind))) {
  if (!token_.empty()) {
    const bool plain = std::all_of(token_.begin(), token_.end(), [](unsigned char c) {
      return std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~';
    });
    if (!plain || token_.size() < 8 || token_.size() > 256) {
      throw Error(
          "the token must be 8-256 letters, digits, '-', '_', '.' or '~' (it travels in a URL and "
          "a cookie)");
    }
  }
  for (std::string& h : allowed_hosts) allowed_hosts_.push_back(host_name_of(h));
  if (!bind_.empty() && bind_.front() == '[') bind_ = host_name_of(bind_);
}

void AccessGuard::set_port(int port) { port_ = port; }

std::string AccessGuard::cookie_name() const { return "lmk_token_" + std::to_string(port_); }

std::string AccessGuard::set_cookie_value() const {
  return cookie_name() + "=" + token_ + "; Path=/; HttpOnly; SameSite=Strict";
}

bool AccessGuard::host_allowed(const std::string& host_header) const {
  const std::string name = host_name_of(host_header);
  if (name.empty()) return false;
  if (is_loopback_name(name) || name == bind_) return true;
  if (std::find(allowed_hosts_.begin(), allowed_hosts_.end(), name) != allowed_hosts_.end()) {
    return true;
  }
  // Listening on every address, the machine is reached by whichever address the client knows; an
  // address written out cannot be rebound to another machine, a name can.
  return is_wildcard(bind_) && is_ip_literal(name);
}

bool AccessGuard::token_matches(const RequestView& r, bool* from_query) const {
  *from_query = false;
  const std::string header = authorization_token(r.authorization);
  if (!header.empty()) return equal_in_constant_time(header, token_);
  if (r.has_query_token) {
    *from_query = equal_in_constant_time(r.query_token, token_);
    return *from_query;
  }
  const std::string cookie = cookie_value(r.cookie, cookie_name());
  return !cookie.empty() && equal_in_constant_time(cookie, token_);
}

AccessVerdict AccessGuard::check(const RequestView& r) const {
  AccessVerdict v;
  if (!host_allowed(r.host)) {
    v.status = 403;
    v.error = "Host '" + printable(r.host) +
              "' is not this server's name (a loopback name or the bound address; lmk serve "
              "--allow-host NAME adds one)";
    return v;
  }
  if (changes_state(r.method) && !r.origin.empty() &&
      lower(r.origin) != "http://" + lower(r.host)) {
    v.status = 403;
    v.error = "cross-origin request refused: Origin '" + printable(r.origin) +
              "' is not this server's own page (http://" + printable(r.host) + ")";
    return v;
  }
  // The API never takes the token from the address: query strings end up in logs, in the
  // browser's history and in Referer headers (issue #61, finding 7). Only the page's one-time
  // ?token= is read, and turned into the cookie.
  if (!token_.empty() && r.has_query_token && r.path.rfind("/api/", 0) == 0) {
    v.status = 401;
    v.error =
        "the API takes its token in the header 'Authorization: token TOKEN' or the page's "
        "cookie, never in the address (?token= only opens the page)";
    return v;
  }
  bool from_query = false;
  v.authenticated = token_.empty() || token_matches(r, &from_query);
  if (!token_.empty() && needs_token(r.path)) {
    if (!v.authenticated) {
      v.status = 401;
      const bool sent = !r.authorization.empty() || r.has_query_token ||
                        !cookie_value(r.cookie, cookie_name()).empty();
      v.error = std::string(sent ? "wrong token" : "this server needs its token") +
                ": open the address lmk serve printed (it ends in ?token=...), or send the header "
                "'Authorization: token TOKEN' (docs/serve.md, \"Access\")";
      return v;
    }
    v.token_from_query = from_query;
  }
  if (changes_state(r.method) && r.has_body && takes_json(r) &&
      media_type(r.content_type) != "application/json") {
    v.status = 415;
    v.error = "send the request's JSON as 'Content-Type: application/json'" +
              (r.content_type.empty() ? std::string(" (no Content-Type was given)")
                                      : " (not '" + printable(r.content_type) + "')");
    return v;
  }
  return v;
}

std::string random_token() {
  std::random_device source;  // the system's random source (/dev/urandom), not a seeded generator
  std::uniform_int_distribution<int> byte(0, 255);
  static constexpr char kHex[] = "0123456789abcdef";
  std::string token;
  for (int i = 0; i < 24; ++i) {
    const int b = byte(source);
    token += kHex[b >> 4];
    token += kHex[b & 15];
  }
  return token;
}

bool equal_in_constant_time(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  unsigned char differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    differ |= static_cast<unsigned char>(a[i]) ^ static_cast<unsigned char>(b[i]);
  }
  return differ == 0;
}

std::string host_name_of(std::string_view host) {
  std::string h = lower(trim(host));
  if (!h.empty() && h.front() == '[') {
    const std::size_t close = h.find(']');
    return close == std::string::npos ? std::string() : h.substr(1, close - 1);
  }
  const std::size_t colon = h.find(':');
  if (colon != std::string::npos && h.find(':', colon + 1) == std::string::npos) {
    h.resize(colon);  // name:port; a bare IPv6 address (two colons or more) keeps them
  }
  return h;
}

bool is_loopback_name(const std::string& address) {
  const std::string a = lower(address);
  return a == "localhost" || a == "::1" || (a.rfind("127.", 0) == 0 && is_ipv4_literal(a));
}

}  // namespace lmk::serve
