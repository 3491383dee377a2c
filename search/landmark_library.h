// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A directory of landmarks, NAME.lmk each: what lmk_node serves and what a person captures into.
// Names are confined to letters, digits, '-', '_' and '.', so that a name from the network can
// never leave the directory. Loaded landmarks, and their search indexes, are kept until their file
// changes.

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "lmk/landmark/landmark.h"
#include "lmk/search/landmark_index.h"

namespace lmk {

class LandmarkLibrary {
 public:
  /// Creates the directory if it does not exist; throws lmk::Error if it cannot.
  explicit LandmarkLibrary(std::filesystem::path directory);

  const std::filesystem::path& directory() const { return directory_; }

  /// The names of the directory's landmarks, sorted.
  std::vector<std::string> names() const;
  /// Where the landmark `name` lives (whether or not it exists); lmk::Error for a bad name.
  std::filesystem::path path_of(const std::string& name) const;
  bool contains(const std::string& name) const;
  /// The landmark `name`, loaded once and again whenever its file changes. Throws lmk::Error for a
  /// bad name, a missing landmark (naming those there are) or a damaged file. Thread-safe.
  std::shared_ptr<const Landmark> load(const std::string& name) const;
  /// The landmark `name` prepared for searches with `settings` (LandmarkIndex), built once and
  /// kept until its file changes or a search with another method, coarse leaf or vote leaf
  /// fraction asks for it. The same errors as load(). Thread-safe.
  std::shared_ptr<const LandmarkIndex> index(const std::string& name,
                                             const FindSettings& settings) const;
  /// Writes `landmark` as NAME.lmk atomically; refuses to replace one unless `overwrite`.
  std::filesystem::path save(const Landmark& landmark, bool overwrite) const;

  /// Throws lmk::Error unless `name` is 1-100 letters, digits, '-', '_' or '.', not starting with
  /// '.' or '-'; the message calls it `kind` ("landmark name", "program id").
  static void check_name(const std::string& name, const std::string& kind = "landmark name");

 private:
  struct Entry {
    std::filesystem::file_time_type modified;
    std::uintmax_t size = 0;
    std::shared_ptr<const Landmark> landmark;
    std::shared_ptr<const LandmarkIndex> index;  ///< of `landmark`, for the last settings asked
  };
  std::filesystem::path directory_;
  mutable std::mutex mutex_;
  mutable std::map<std::string, Entry> cache_;
};

}  // namespace lmk
