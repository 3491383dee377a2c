// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Scene datasets for batch evaluation (docs/datasets.md): a directory holding dataset.json,
// scene clouds, landmark files and the ground truth of every (scene, landmark) pair.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "lmk/geometry/symmetry.h"

namespace lmk {

inline constexpr int kDatasetFormatVersion = 1;

struct DatasetLandmark {
  std::string name;
  std::string file;  ///< .lmk, relative to the dataset directory
  Symmetry symmetry;
};

/// How far a pair's ground truth moved when its two frames were registered: real sequences, whose
/// camera poses come from reconstruction, record it (lmk gen --from-rgbd).
struct PoseCheck {
  double translation = 0.0;  ///< at the landmark's box centre, m
  double rotation = 0.0;     ///< rad
};

/// The ground truth of one (scene, landmark) pair. Pairs a scene does not list are out of context
/// and hold no instance.
struct DatasetPair {
  std::string landmark;
  bool in_context = true;
  std::vector<Eigen::Isometry3d> instances;  ///< box poses in the scene frame
  /// Optional: for each instance, the fraction of the landmark the scene's sensor does not see
  /// (sim/instance_visibility.h), in [0, 1]; empty when the dataset does not record it.
  std::vector<double> hidden;
  std::optional<PoseCheck> pose_check;  ///< optional: the registration's disagreement
};

struct DatasetScene {
  std::string name;
  std::string file;     ///< point cloud, relative to the dataset directory
  std::string setting;  ///< "simple", "cluttered", "unconventional", or free text
  Eigen::Isometry3d T_scene_sensor = Eigen::Isometry3d::Identity();
  /// The scene's up axis (unit, scene frame), where the scene frame has one (a world or robot
  /// base frame). Unset: the sensor's -y, as for any camera-frame cloud.
  std::optional<Eigen::Vector3d> up;
  std::vector<DatasetPair> pairs;
};

struct Dataset {
  std::string name;
  std::vector<DatasetLandmark> landmarks;
  std::vector<DatasetScene> scenes;

  /// The pair of `scene` with `landmark`, or an out-of-context pair without instances.
  DatasetPair pair(const DatasetScene& scene, const std::string& landmark) const;
};

/// One scene's entry as dataset.json lists it, as JSON text: what a shard of a sharded generation
/// writes for each scene it renders, for the merge to gather (lmk gen --shard, --merge).
std::string scene_entry_text(const DatasetScene& scene);
/// Reads such an entry; lmk::Error naming `where` (its file) and the field that is wrong.
DatasetScene parse_scene_entry(const std::string& text, const std::string& where);

/// Where the scene and landmark files a dataset.json names may lie.
enum class DatasetFiles {
  /// Inside the dataset's directory, after every symbolic link (the default): a dataset from
  /// elsewhere cannot make lmk read ../../secret or /etc/passwd as a scene (issue #34, finding 5).
  inside,
  /// Anywhere (lmk eval --allow-outside-files): a dataset that points at shared data on purpose.
  anywhere,
};

/// Reads and validates DIR/dataset.json. Throws lmk::Error naming the file, the field path (e.g.
/// scenes[2].pairs[0].landmark) and the problem: a wrong version, a missing file, a special file
/// (a named pipe, a device), a symbolic link loop, a file outside DIR (unless `files` allows it),
/// a duplicate or unknown name, a bad pose (non-finite, or a quaternion that is not unit length).
Dataset load_dataset(const std::string& dir, DatasetFiles files = DatasetFiles::inside);

/// Validates `dataset` against `dir` (the files it names must exist there) and writes
/// DIR/dataset.json atomically.
void save_dataset(const std::string& dir, const Dataset& dataset);

/// The name of the landmark of `views` views cut with the box of landmark `name` (lmk gen --views,
/// issue #35): `name` itself for one view, "<name>-v<views>" beyond.
std::string views_landmark_name(const std::string& name, std::size_t views);

struct Landmark;

/// A hash of what a dataset holds: dataset.json, the scene files, and each landmark's points, box
/// and up axis. Raw .lmk bytes are not hashed because OpenVDB writes a random id into every file.
/// Two datasets with the same fingerprint give the same evaluation (dataset_fingerprint.cpp).
std::string dataset_fingerprint(const std::string& dir, const Dataset& dataset);
/// The same with the dataset's landmarks already loaded, in dataset order.
std::string dataset_fingerprint(const std::string& dir, const Dataset& dataset,
                                const std::vector<Landmark>& landmarks);

}  // namespace lmk
