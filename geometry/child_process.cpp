// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/child_process.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <string>

#include "lmk/geometry/error.h"

namespace lmk {
namespace {

// The child's first byte says what follows: its answer, an lmk::Error's message, or another
// exception's.
constexpr char kAnswer = 'A', kLmkError = 'E', kOtherError = 'X';

bool write_all(int fd, const char* data, std::size_t n) {
  while (n > 0) {
    const ssize_t written = ::write(fd, data, n);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) return false;
    data += written;
    n -= static_cast<std::size_t>(written);
  }
  return true;
}

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

// Limits the data this process maps to what it holds now (VmData, which counts what the parent
// held) plus `extra` bytes.
void limit_data(std::size_t extra) {
  std::ifstream status("/proc/self/status");
  std::size_t held_kb = 0;
  for (std::string key; status >> key;) {
    if (key == "VmData:") {
      status >> held_kb;
      break;
    }
    status.ignore(1 << 16, '\n');
  }
  if (held_kb == 0) return;
  const rlim_t limit = static_cast<rlim_t>(held_kb) * 1024 + extra;
  const rlimit data{limit, limit};
  ::setrlimit(RLIMIT_DATA, &data);
}

[[noreturn]] void be_the_child(int fd, const std::function<std::string()>& work,
                               std::size_t extra_memory) {
  if (!kSanitized) limit_data(extra_memory);
  char kind = kAnswer;
  std::string out;
  try {
    out = work();
  } catch (const Error& e) {
    kind = kLmkError;
    out = e.what();
  } catch (const std::exception& e) {
    kind = kOtherError;
    out = e.what();
  } catch (...) {
    kind = kOtherError;
    out = "an unknown exception";
  }
  const bool sent = write_all(fd, &kind, 1) && write_all(fd, out.data(), out.size());
  ::_exit(sent ? 0 : 1);
}

std::string read_all(int fd) {
  std::string in;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof(buffer));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return in;
    in.append(buffer, static_cast<std::size_t>(n));
  }
}

}  // namespace

bool child_memory_is_limited() { return !kSanitized; }

std::string run_in_child(const std::function<std::string()>& work, const std::string& what,
                         std::size_t extra_memory) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    throw Error(what + ": cannot open a pipe to a child process (" + std::strerror(errno) + ")");
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int error = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    throw Error(what + ": cannot start a child process (" + std::strerror(error) + ")");
  }
  if (pid == 0) {
    ::close(fds[0]);
    be_the_child(fds[1], work, extra_memory);
  }
  ::close(fds[1]);
  std::string reply = read_all(fds[0]);
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    throw Error(what + ": the process reading it crashed (signal " + std::to_string(signal) + ", " +
                strsignal(signal) + ")");
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || reply.empty()) {
    throw Error(what + ": the process reading it ended without an answer");
  }
  const char kind = reply[0];
  reply.erase(0, 1);
  if (kind == kLmkError) throw Error(reply);
  if (kind != kAnswer) throw Error(what + ": " + reply);
  return reply;
}

}  // namespace lmk
