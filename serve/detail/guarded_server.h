// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// httplib's server with the connection limits of connection_limits.h: each connection is read
// through a stream that stops at its deadline, or when a newer connection of the same client cut
// it off, instead of waiting as long as bytes keep trickling in.
#include <httplib.h>

#include "lmk/serve/connection_limits.h"

namespace lmk::serve::detail {

class GuardedServer : public httplib::Server {
 public:
  explicit GuardedServer(ConnectionTable& table) : table_(table) {}

 private:
  // httplib's keep-alive loop, with the table's deadlines (httplib 0.11 declares this hook
  // virtual for servers that serve their sockets their own way).
  bool process_and_close_socket(socket_t sock) override;

  ConnectionTable& table_;
};

}  // namespace lmk::serve::detail
