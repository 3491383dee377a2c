// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The scenes `lmk serve` shows: the files it was started with and the clouds uploaded since, each
// under an id that the API uses instead of a path, so that no request names a file.
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/depth_correction.h"
#include "lmk/geometry/point_cloud.h"
#include "lmk/landmark/scene_settings.h"
#include "lmk/serve/memory_budget.h"

namespace lmk::serve {

struct Scene {
  std::string id;      ///< "1", "2", ...: never reused
  std::string name;    ///< the file's name
  std::string source;  ///< "file" or "upload"
  /// Holds the scene's share of the memory budget for as long as anyone (a job) holds it.
  std::shared_ptr<const PointCloud> cloud;
};

/// A file of the scratch directory that an upload's bytes are written to as they arrive, so that
/// no upload is ever whole in memory before it is parsed; removed with this object.
class UploadFile {
 public:
  UploadFile(std::string name, std::filesystem::path path);
  ~UploadFile();
  UploadFile(const UploadFile&) = delete;
  UploadFile& operator=(const UploadFile&) = delete;
  const std::string& name() const { return name_; }  ///< the client's name for it
  const std::filesystem::path& path() const { return path_; }
  /// Appends bytes; lmk::Error when the disk refuses them.
  void write(const char* data, std::size_t n);
  /// Flushes and closes; the bytes written.
  std::size_t close();

 private:
  std::string name_;
  std::filesystem::path path_;
  std::FILE* file_;
  std::size_t bytes_ = 0;
};

/// What uploads may hold (docs/serve.md, "Safety"): a 50-million-point upload kept 590 MB
/// resident, and 16 were kept (issue #34, finding 3).
struct UploadLimits {
  std::size_t max_uploads = 16;              ///< uploaded scenes kept; the oldest goes first
  std::size_t max_points = 5'000'000;        ///< points of one upload (a 1080p frame has 2 million)
  std::size_t max_kept_points = 20'000'000;  ///< points of all uploads kept; the oldest go first
};

class SceneStore {
 public:
  /// Keeps uploads within `limits` and every scene's memory within `budget` (which must outlive
  /// the store and its scenes); uploads are parsed in `scratch_dir`. A `correction` (the depth
  /// camera's error) is undone on every scene read or uploaded.
  SceneStore(UploadLimits limits, std::filesystem::path scratch_dir, MemoryBudget& budget,
             std::optional<DepthCorrection> correction = {});

  /// Reads a scene file given on the command line; lmk::Error for a bad one.
  Scene add_file(const std::string& path);
  /// A new scratch file for the upload `name`; ApiError 400 for no name, or one that is not a
  /// plain file name with a cloud's extension.
  std::unique_ptr<UploadFile> new_upload_file(const std::string& name) const;
  /// Parses an uploaded cloud (its name's extension gives the format). Priced before it is read,
  /// from the file's size and the points its header declares: 413 for more than
  /// limits.max_points points (from the header, or while an XYZ file is read) or a price over the
  /// whole budget, 503 when the budget has no room now. ApiError 400 for a malformed cloud or one
  /// the depth correction does not fit, with the message. The oldest uploads go to keep within
  /// the limits.
  Scene add_upload(UploadFile& file);
  /// The same for bytes in memory (the fuzzer's way in).
  Scene add_upload(const std::string& name, const std::string& bytes);
  /// What indexing `scene` with `settings` and searching it takes at its peak
  /// (estimate_scene_footprint), remembered per scene and settings; ApiError 413 when it is more
  /// than the whole budget.
  std::size_t search_footprint(const Scene& scene, const SceneSettings& settings);
  /// The scene `id`; ApiError 404 naming the ids there are.
  Scene get(const std::string& id) const;
  std::vector<Scene> list() const;

 private:
  Scene& insert(std::string name, std::string source, PointCloud cloud,
                MemoryBudget::Reservation memory);

  UploadLimits limits_;
  MemoryBudget& budget_;
  std::filesystem::path scratch_dir_;
  std::optional<DepthCorrection> correction_;
  mutable std::mutex mutex_;
  std::vector<Scene> scenes_;
  std::size_t next_id_ = 1;
  std::map<std::string, std::size_t> footprints_;  // by scene id and settings
};

}  // namespace lmk::serve
