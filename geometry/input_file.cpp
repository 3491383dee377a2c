// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "lmk/geometry/error.h"

namespace lmk {

namespace {

const char* special_file_name(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a named pipe";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

std::string describe_bytes(std::uintmax_t bytes) {
  if (bytes < 1024) return std::to_string(bytes) + " bytes";
  const char* units[] = {"KiB", "MiB", "GiB", "TiB"};
  double value = static_cast<double>(bytes) / 1024.0;
  int unit = 0;
  while (value >= 1024.0 && unit < 3) {
    value /= 1024.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof(text), value == static_cast<int>(value) ? "%.0f %s" : "%.1f %s", value,
                units[unit]);
  return text;
}

std::uintmax_t check_input_file(const std::string& path, const InputKind& kind) {
  // stat, not open: opening a named pipe for reading blocks until a writer appears.
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) throw Error(path + ": no such file");
    throw Error(path + ": cannot read (" + std::strerror(errno) + ")");
  }
  if (!S_ISREG(info.st_mode)) {
    throw Error(path + ": is " + special_file_name(info.st_mode) + ", not a " + kind.name);
  }
  const auto size = static_cast<std::uintmax_t>(info.st_size);
  if (size > kind.max_bytes) {
    throw Error(path + ": is " + std::to_string(size) + " bytes, over lmk's limit of " +
                describe_bytes(kind.max_bytes) + " for a " + kind.name);
  }
  return size;
}

std::string read_input_file(const std::string& path, const InputKind& kind) {
  const std::uintmax_t size = check_input_file(path, kind);
  // O_NONBLOCK: should the path have become a pipe since the check, the open does not hang.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw Error(path + ": cannot open for reading (" + std::strerror(errno) + ")");
  std::string bytes;
  bytes.reserve(static_cast<std::size_t>(size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof(buffer));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::string reason = std::strerror(errno);
      ::close(fd);
      throw Error(path + ": cannot read (" + reason + ")");
    }
    if (n == 0) break;
    bytes.append(buffer, static_cast<std::size_t>(n));
    if (bytes.size() > kind.max_bytes) {  // grew while being read
      ::close(fd);
      throw Error(path + ": grew over lmk's limit of " + describe_bytes(kind.max_bytes) +
                  " for a " + kind.name + " while being read");
    }
  }
  ::close(fd);
  return bytes;
}

bool lies_within(const std::filesystem::path& path, const std::filesystem::path& root,
                 std::error_code& ec) {
  const std::filesystem::path real = std::filesystem::weakly_canonical(path, ec);
  if (ec) return false;
  const std::filesystem::path base = std::filesystem::canonical(root, ec);
  if (ec) return false;
  const auto [end, ignored] = std::mismatch(base.begin(), base.end(), real.begin(), real.end());
  return end == base.end();
}

}  // namespace lmk
