#include "geometry/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <string>
#include <system_error>

#include "geometry/error.h"

namespace lmk {

namespace fs = std::filesystem;

void write_file_atomically(const fs::path& path,
                           const std::function<void(const fs::path&)>& write) {
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw Error(path.string() + ": cannot write: directory '" + dir.string() + "' does not exist");
  }
  // Unique per process and per call, so concurrent writers never share a temporary. The extension
  // is kept last because some writers choose their format from it.
  static std::atomic<unsigned> counter{0};
  const fs::path tmp = dir / ("." + path.stem().string() + ".tmp" + std::to_string(::getpid()) +
                              "-" + std::to_string(counter++) + path.extension().string());
  try {
    write(tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw Error(path.string() + ": cannot write: " + ec.message());
  }
}

void write_text_atomically(const fs::path& path, const std::string& text) {
  write_file_atomically(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out) throw Error(path.string() + ": write failed");
  });
}

}  // namespace lmk
