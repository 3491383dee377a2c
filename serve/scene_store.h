// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The scenes `lmk serve` shows: the files it was started with and the clouds uploaded since, each
// under an id that the API uses instead of a path, so that no request names a file.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/depth_correction.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk::serve {

struct Scene {
  std::string id;      ///< "1", "2", ...: never reused
  std::string name;    ///< the file's name
  std::string source;  ///< "file" or "upload"
  std::shared_ptr<const PointCloud> cloud;
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
  /// Keeps uploads within `limits`; uploads are parsed in `scratch_dir`. A `correction` (the depth
  /// camera's error) is undone on every scene read or uploaded.
  SceneStore(UploadLimits limits, std::filesystem::path scratch_dir,
             std::optional<DepthCorrection> correction = {});

  /// Reads a scene file given on the command line; lmk::Error for a bad one.
  Scene add_file(const std::string& path);
  /// Parses an uploaded cloud named `name` (its extension gives the format). ApiError 400 for a
  /// bad name, a malformed cloud or one the depth correction does not fit, with the message; 413
  /// for more than limits.max_points points. The oldest uploads go to keep within the limits.
  Scene add_upload(const std::string& name, const std::string& bytes);
  /// The scene `id`; ApiError 404 naming the ids there are.
  Scene get(const std::string& id) const;
  std::vector<Scene> list() const;

 private:
  Scene& insert(std::string name, std::string source, PointCloud cloud);

  UploadLimits limits_;
  std::filesystem::path scratch_dir_;
  std::optional<DepthCorrection> correction_;
  mutable std::mutex mutex_;
  std::vector<Scene> scenes_;
  std::size_t next_id_ = 1;
};

}  // namespace lmk::serve
