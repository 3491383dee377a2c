// SPDX-License-Identifier: BSD-3-Clause
// The lmk command line end to end: lmk serve's refusals, address and token.

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "lmk/geometry/pose.h"
#include "tests/cli/cli_fixture.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

using test::CommandResult;

TEST_F(Cli, ServeRefusesBadScenesAndPortsWithOneLine) {
  expect_bad_input("serve " + path("missing.pcd"), "missing.pcd");
  test::write_text(dir_.file("notes.txt"), "hello\n");
  expect_bad_input("serve " + path("notes.txt"), ".pcd");
  test::write_text(dir_.file("broken.pcd"), "VERSION .7\nFIELDS x y z\nPOINTS 9\n");
  expect_bad_input("serve " + path("broken.pcd"), "broken.pcd");
  expect_bad_input("serve --port 70000", "70000");
  expect_bad_input("serve --workers 0", "workers");
}

// Runs `lmk serve ARGS` in the background until it prints its address (at most 60 s), then sends
// it SIGINT, as Ctrl-C.
CommandResult serve_then_interrupt(const test::ScratchDir& dir, const std::string& args) {
  const std::string out = dir.file("stdout"), err = dir.file("stderr");
  const std::string command =
      "rm -f '" + out + "' '" + err + "'; '" + std::string(LMK_BINARY) + "' serve " + args + " >'" +
      out + "' 2>'" + err + "' & pid=$!; for i in $(seq 600); do grep -q '^open http' '" + out +
      "' && break; kill -0 $pid 2>/dev/null || break; sleep 0.1; done; kill -INT $pid; wait $pid";
  const int status = std::system(command.c_str());
  return CommandResult{WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

TEST_F(Cli, ServeWarnsOnAnAddressOtherThanLoopbackAndStopsOnCtrlC) {
  const std::string landmarks = " --landmarks " + path("landmarks");
  const CommandResult r = serve_then_interrupt(dir_, "--bind 0.0.0.0 --port 0 --quiet" + landmarks);
  EXPECT_EQ(r.exit_code, 0) << r.err;  // stopped cleanly
  EXPECT_NE(r.err.find("warning: --bind 0.0.0.0"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("open http://0.0.0.0:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("lmk serve: stopped"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::is_directory(dir_.file("landmarks")));
  const CommandResult loopback = serve_then_interrupt(dir_, "--port 0 --quiet" + landmarks);
  EXPECT_EQ(loopback.exit_code, 0) << loopback.err;
  EXPECT_NE(loopback.out.find("open http://127.0.0.1:"), std::string::npos) << loopback.out;
  EXPECT_EQ(loopback.err.find("warning"), std::string::npos) << loopback.err;
}

TEST_F(Cli, ServePrintsItsTokenInTheAddressAndAsksOneOffLoopback) {
  const std::string args = "--port 0 --quiet --landmarks " + path("landmarks");
  const std::regex address(R"(open http://127\.0\.0\.1:[0-9]+/\?token=([0-9a-f]{48}) \(Ctrl-C)");
  const CommandResult first = serve_then_interrupt(dir_, args);
  const CommandResult second = serve_then_interrupt(dir_, args);
  std::smatch a, b;
  ASSERT_TRUE(std::regex_search(first.out, a, address)) << first.out;
  ASSERT_TRUE(std::regex_search(second.out, b, address)) << second.out;
  EXPECT_NE(a[1].str(), b[1].str()) << "a fresh token each start";

  const CommandResult chosen = serve_then_interrupt(dir_, args + " --token my-own-token");
  EXPECT_NE(chosen.out.find("/?token=my-own-token "), std::string::npos) << chosen.out;
  expect_bad_input("serve --port 0 --landmarks " + path("landmarks") + " --token short",
                   "the token must be 8-256");
  ::setenv("LMK_SERVE_TOKEN", "token-from-environment", 1);
  const CommandResult env = serve_then_interrupt(dir_, args);
  ::unsetenv("LMK_SERVE_TOKEN");
  EXPECT_NE(env.out.find("/?token=token-from-environment "), std::string::npos) << env.out;

  const CommandResult open = serve_then_interrupt(dir_, args + " --no-token");
  EXPECT_EQ(open.exit_code, 0) << open.err;
  EXPECT_NE(open.err.find("warning: --no-token"), std::string::npos) << open.err;
  EXPECT_EQ(open.out.find("token="), std::string::npos) << open.out;
  expect_bad_input("serve --no-token --bind 0.0.0.0 --port 0 --landmarks " + path("landmarks"),
                   "--no-token is only allowed on a loopback address");
}

TEST_F(Cli, ServeOnAPortInUseIsOneLine) {
  // The test holds a listening socket on a free port of loopback; lmk serve is asked for it.
  const int socket_fd = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(socket_fd, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof(address);
  ASSERT_EQ(::bind(socket_fd, reinterpret_cast<sockaddr*>(&address), length), 0);
  ASSERT_EQ(::listen(socket_fd, 1), 0);
  ASSERT_EQ(::getsockname(socket_fd, reinterpret_cast<sockaddr*>(&address), &length), 0);
  const std::string port = std::to_string(ntohs(address.sin_port));
  expect_bad_input("serve --quiet --landmarks " + path("lm") + " --port " + port,
                   "cannot listen on 127.0.0.1:" + port);
  ::close(socket_fd);
}

}  // namespace
}  // namespace lmk
