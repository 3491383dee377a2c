// SPDX-License-Identifier: BSD-3-Clause
#include "tests/support/test_support.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "lmk/geometry/random.h"

namespace lmk::test {

namespace fs = std::filesystem;

PointCloud random_cloud(std::size_t n, std::uint64_t seed, float half) {
  SplitMix64 rng(seed);
  PointCloud cloud;
  for (std::size_t i = 0; i < n; ++i) {
    cloud.points.emplace_back(
        Eigen::Vector3d(rng.uniform01(), rng.uniform01(), rng.uniform01()).cast<float>() *
            (2.0f * half) -
        Eigen::Vector3f::Constant(half));
  }
  cloud.set_unorganized();
  return cloud;
}

ScratchDir::ScratchDir() {
  static std::atomic<int> counter{0};
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "lmk";
  path_ = fs::temp_directory_path() /
          ("lmk-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" + name);
  fs::remove_all(path_);
  fs::create_directories(path_);
}

ScratchDir::~ScratchDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

CommandResult run_shell(const std::string& command, const ScratchDir& dir) {
  const std::string out = dir.file("stdout"), err = dir.file("stderr");
  const int status = std::system((command + " >'" + out + "' 2>'" + err + "'").c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_bytes(out), read_bytes(err)};
}

fs::path shared_run_data(const std::string& name,
                         const std::function<void(const fs::path&)>& make) {
  const char* root = std::getenv("LMK_TEST_RUN_DIR");
  if (!root || !*root) {
    static std::vector<std::unique_ptr<ScratchDir>> scratch;  // kept for the process's lifetime
    scratch.push_back(std::make_unique<ScratchDir>());
    const fs::path dir = scratch.back()->path() / name;
    fs::create_directories(dir);
    make(dir);
    return dir;
  }
  fs::create_directories(root);
  const fs::path dir = fs::path(root) / name;
  const std::string lock = (fs::path(root) / (name + ".lock")).string();
  const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error("shared_run_data: cannot open " + lock);
  // Waits for the test making the data to finish (an event, not a time), or makes it.
  if (::flock(fd, LOCK_EX) != 0) {
    ::close(fd);
    throw std::runtime_error("shared_run_data: cannot lock " + lock);
  }
  try {
    if (!fs::exists(dir)) {
      // Made aside and renamed: a test killed while making it leaves no half-made data behind.
      const fs::path partial = fs::path(root) / (name + ".partial");
      fs::remove_all(partial);
      fs::create_directories(partial);
      make(partial);
      fs::rename(partial, dir);
    }
  } catch (...) {
    ::close(fd);  // releases the lock
    throw;
  }
  ::close(fd);
  return dir;
}

std::optional<fs::path> shared_data_dir() {
  const char* env = std::getenv("LMK_SHARED_DATA");
  const fs::path dir = env && *env ? fs::path(env) : fs::path(LMK_SHARED_DATA_DIR);
  std::error_code ec;
  if (fs::is_directory(dir / "pcl", ec)) return dir;
  return std::nullopt;
}

double process_status_bytes(const std::string& field, const std::string& pid) {
  std::ifstream status("/proc/" + pid + "/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind(field + ":", 0) == 0) return std::stod(line.substr(field.size() + 1)) * 1024.0;
  }
  return 0.0;
}

bool reset_peak_memory() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.close();
  return static_cast<bool>(clear);
}

std::size_t write_zero_compressed_pcd(const std::string& path, std::size_t points,
                                      const std::vector<std::string>& fields,
                                      std::size_t pad_count) {
  std::string names, sizes, types, counts;
  for (const std::string& f : fields) {
    names += " " + f;
    sizes += " 4";
    types += " F";
    counts += " 1";
  }
  const std::uint64_t expanded = points * 4 * (fields.size() + pad_count);
  if (expanded >= (std::uint64_t{1} << 32)) throw std::invalid_argument("over PCD's 4 GB block");
  std::string block;
  std::uint64_t written = 0;
  if (expanded > 0) {
    block += std::string("\0\0", 2);  // a literal run of one zero byte
    written = 1;
  }
  while (written < expanded) {
    const std::uint64_t n = std::min<std::uint64_t>(264, expanded - written);
    if (n < 3) {  // too short for a back reference: a literal run
      block += static_cast<char>(n - 1);
      block += std::string(n, '\0');
    } else if (n - 2 < 7) {
      block += static_cast<char>((n - 2) << 5);
      block += '\0';  // distance 1
    } else {
      block += static_cast<char>(7 << 5);
      block += static_cast<char>(n - 2 - 7);
      block += '\0';
    }
    written += n;
  }
  std::ostringstream header;
  header << "# .PCD v0.7\nVERSION 0.7\nFIELDS" << names << (pad_count > 0 ? " pad" : "") << "\nSIZE"
         << sizes << (pad_count > 0 ? " 4" : "") << "\nTYPE" << types << (pad_count > 0 ? " F" : "")
         << "\nCOUNT" << counts << (pad_count > 0 ? " " + std::to_string(pad_count) : "")
         << "\nWIDTH " << points << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << points
         << "\nDATA binary_compressed\n";
  const std::uint32_t sizes_field[2] = {static_cast<std::uint32_t>(block.size()),
                                        static_cast<std::uint32_t>(expanded)};
  std::string bytes = header.str();
  bytes.append(reinterpret_cast<const char*>(sizes_field), sizeof(sizes_field));
  bytes += block;
  write_text(path, bytes);
  return bytes.size();
}

}  // namespace lmk::test
