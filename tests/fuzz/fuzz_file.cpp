// SPDX-License-Identifier: BSD-3-Clause
#include "tests/fuzz/fuzz_file.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace lmk::fuzz {

namespace fs = std::filesystem;

namespace {

fs::path make_scratch_dir() {
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/lmk-fuzz-XXXXXX";
  if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot create " + pattern);
  return pattern;
}

}  // namespace

const std::string& scratch_dir() {
  static const std::string dir = [] {
    const fs::path path = make_scratch_dir();
    static const fs::path removed_at_exit = path;
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(removed_at_exit, ec);
    });
    return path.string();
  }();
  return dir;
}

std::string write_input(const std::string& name, const unsigned char* data, std::size_t size) {
  const std::string path = scratch_dir() + "/" + name;
  std::FILE* out = std::fopen(path.c_str(), "wb");
  if (out == nullptr) throw std::runtime_error("cannot write " + path);
  if (size > 0) std::fwrite(data, 1, size, out);
  std::fclose(out);
  return path;
}

}  // namespace lmk::fuzz
