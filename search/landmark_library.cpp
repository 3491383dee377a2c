// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/landmark_library.h"

#include <algorithm>
#include <cctype>

#include "lmk/geometry/error.h"
#include "lmk/geometry/plain_name.h"
#include "lmk/landmark/landmark_file.h"

namespace lmk {

namespace fs = std::filesystem;

LandmarkLibrary::LandmarkLibrary(fs::path directory) : directory_(std::move(directory)) {
  std::error_code ec;
  fs::create_directories(directory_, ec);
  if (ec || !fs::is_directory(directory_)) {
    throw Error(directory_.string() + ": cannot use as the landmark directory" +
                (ec ? " (" + ec.message() + ")" : ""));
  }
}

void LandmarkLibrary::check_name(const std::string& name, const std::string& kind) {
  // printable(): a NUL or a byte that is not UTF-8 would cut the message short or make the page's
  // JSON invalid (issue #34, finding 5).
  if (!is_plain_name(name, 100)) {
    throw Error(kind + " '" + printable(name) +
                "': use 1 to 100 letters, digits, '-', '_' or '.', not starting with '.' or '-'");
  }
}

std::vector<std::string> LandmarkLibrary::names() const {
  std::vector<std::string> out;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(directory_, ec)) {
    const fs::path& p = entry.path();
    if (p.extension() != ".lmk" || !entry.is_regular_file()) continue;
    const std::string name = p.stem().string();
    try {
      check_name(name);
      out.push_back(name);
    } catch (const Error&) {
      // A file no client could name is not part of the library.
    }
  }
  if (ec) throw Error(directory_.string() + ": cannot list (" + ec.message() + ")");
  std::sort(out.begin(), out.end());
  return out;
}

fs::path LandmarkLibrary::path_of(const std::string& name) const {
  check_name(name);
  return directory_ / (name + ".lmk");
}

bool LandmarkLibrary::contains(const std::string& name) const {
  return fs::is_regular_file(path_of(name));
}

std::shared_ptr<const Landmark> LandmarkLibrary::load(const std::string& name) const {
  const fs::path path = path_of(name);
  std::error_code ec;
  const fs::file_time_type modified = fs::last_write_time(path, ec);
  if (ec) {
    std::string known;
    for (const std::string& n : names()) known += (known.empty() ? "" : ", ") + n;
    throw Error("no landmark '" + name + "' in " + directory_.string() + " (it holds " +
                (known.empty() ? "none" : known) + ")");
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = cache_.find(name);
    if (it != cache_.end() && it->second.modified == modified && it->second.size == size) {
      return it->second.landmark;
    }
  }
  auto landmark = std::make_shared<const Landmark>(load_landmark(path.string()));
  const std::lock_guard<std::mutex> lock(mutex_);
  cache_[name] = Entry{modified, size, landmark, nullptr};
  return landmark;
}

std::shared_ptr<const LandmarkIndex> LandmarkLibrary::index(const std::string& name,
                                                            const FindSettings& settings) const {
  const std::shared_ptr<const Landmark> landmark = load(name);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = cache_.find(name);
    if (it != cache_.end() && it->second.index && &it->second.index->landmark() == landmark.get() &&
        it->second.index->suits(settings)) {
      return it->second.index;
    }
  }
  // Built outside the lock: two threads may build the same index once each, which is harmless.
  auto built = std::make_shared<const LandmarkIndex>(landmark, settings);
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto it = cache_.find(name);
  if (it != cache_.end() && it->second.landmark == landmark) it->second.index = built;
  return built;
}

fs::path LandmarkLibrary::save(const Landmark& landmark, bool overwrite) const {
  const fs::path path = path_of(landmark.name);
  if (!overwrite && fs::exists(path)) {
    throw Error("a landmark '" + landmark.name + "' exists already (" + path.string() +
                "); ask to overwrite it, or choose another name");
  }
  save_landmark(path.string(), landmark);
  return path;
}

}  // namespace lmk
