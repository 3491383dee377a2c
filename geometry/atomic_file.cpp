// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <fstream>
#include <string>
#include <system_error>

#include "lmk/geometry/error.h"

namespace lmk {

namespace fs = std::filesystem;

namespace {

// The temporary beside `path` for this process's `serial`-th write: ".STEM.tmpPID-SERIAL.EXT". The
// extension is kept last because some writers choose their format from it.
fs::path temporary_for(const fs::path& dir, const fs::path& path, long pid, unsigned serial) {
  return dir / ("." + path.stem().string() + ".tmp" + std::to_string(pid) + "-" +
                std::to_string(serial) + path.extension().string());
}

// The process id in a temporary's name if it is one of `path`'s temporaries, else -1.
long writer_of(const std::string& name, const fs::path& path) {
  const std::string prefix = "." + path.stem().string() + ".tmp";
  const std::string suffix = path.extension().string();
  if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return -1;
  }
  const std::string middle =
      name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  const std::size_t dash = middle.find('-');
  if (dash == 0 || dash == std::string::npos || dash + 1 == middle.size()) return -1;
  for (std::size_t i = 0; i < middle.size(); ++i) {
    if (i != dash && !std::isdigit(static_cast<unsigned char>(middle[i]))) return -1;
  }
  return std::stol(middle.substr(0, dash));
}

// Removes the temporaries of `path` left by writers that are gone (killed before their rename).
// A live writer's temporary is kept: two processes may write the same target at once.
void remove_stale_temporaries(const fs::path& dir, const fs::path& path) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const long pid = writer_of(it->path().filename().string(), path);
    if (pid <= 0) continue;
    if (process_has_ended(pid)) fs::remove(it->path(), ec);
  }
}

// Flushes `path` (a file or a directory) to the disk, so that a crash after the rename finds the
// new contents, not an empty file. Errors are returned, not thrown.
std::error_code sync_to_disk(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return {errno, std::generic_category()};
  const int status = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  return status == 0 ? std::error_code() : std::error_code(error, std::generic_category());
}

// `message` with every mention of the temporary replaced by the target: users know the target.
std::string naming_target(std::string message, const fs::path& tmp, const fs::path& path) {
  const std::string from = tmp.string(), to = path.string();
  for (std::size_t at = message.find(from); at != std::string::npos;
       at = message.find(from, at + to.size())) {
    message.replace(at, from.size(), to);
  }
  return message;
}

}  // namespace

void write_file_atomically(const fs::path& path,
                           const std::function<void(const fs::path&)>& write) {
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw Error(path.string() + ": cannot write: directory '" + dir.string() + "' does not exist");
  }
  if (fs::is_directory(path, ec)) throw Error(path.string() + ": cannot write: it is a directory");
  remove_stale_temporaries(dir, path);
  // Unique per process and per call, so concurrent writers never share a temporary.
  static std::atomic<unsigned> counter{0};
  const fs::path tmp = temporary_for(dir, path, static_cast<long>(::getpid()), counter++);
  std::error_code ignored;
  try {
    write(tmp);
  } catch (const Error& e) {
    fs::remove(tmp, ignored);
    throw Error(naming_target(e.what(), tmp, path));
  } catch (...) {
    fs::remove(tmp, ignored);
    throw;
  }
  if (const std::error_code sync = sync_to_disk(tmp)) {
    fs::remove(tmp, ignored);
    throw Error(path.string() + ": cannot write: " + sync.message());
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ignored);  // its own error code: `ec` holds the reason to report
    throw Error(path.string() + ": cannot write: " + ec.message());
  }
  sync_to_disk(dir);  // the rename itself; a directory that cannot be synced loses nothing else
}

void write_text_atomically(const fs::path& path, const std::string& text) {
  write_file_atomically(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.flush();
    if (!out) throw Error(path.string() + ": write failed");
  });
}

bool process_has_ended(long pid) {
  // kill(pid, 0) sends nothing; ESRCH alone means no such process (EPERM: alive, someone else's).
  return pid > 0 && pid != ::getpid() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

}  // namespace lmk
