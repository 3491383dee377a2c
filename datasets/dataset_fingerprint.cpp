// SPDX-License-Identifier: BSD-3-Clause
#include <filesystem>

#include "lmk/datasets/dataset.h"
#include "lmk/geometry/hash.h"
#include "lmk/geometry/input_file.h"
#include "lmk/landmark/landmark_file.h"

namespace lmk {
namespace {

namespace fs = std::filesystem;

std::string read_bytes(const fs::path& path) { return read_input_file(path.string(), kCloudInput); }

}  // namespace

std::string dataset_fingerprint(const std::string& dir, const Dataset& dataset) {
  std::vector<Landmark> landmarks;
  for (const DatasetLandmark& entry : dataset.landmarks)
    landmarks.push_back(load_landmark((fs::path(dir) / entry.file).string()));
  return dataset_fingerprint(dir, dataset, landmarks);
}

std::string dataset_fingerprint(const std::string& dir, const Dataset& dataset,
                                const std::vector<Landmark>& landmarks) {
  Fnv1a hash;
  hash.add(read_bytes(fs::path(dir) / "dataset.json"));
  for (const DatasetScene& scene : dataset.scenes) hash.add(read_bytes(fs::path(dir) / scene.file));
  for (const Landmark& landmark : landmarks) {
    for (const Eigen::Vector3f& p : landmark.points.points) hash.add(p.data(), sizeof(float) * 3);
    // Colour only where there is some: an uncoloured landmark keeps the fingerprint it had.
    for (const Color& c : landmark.points.colors) hash.add(&c, sizeof(Color));
    const Eigen::Matrix4d box_pose = landmark.box.pose.matrix();
    hash.add(box_pose.data(), sizeof(double) * 16)
        .add(landmark.box.size.data(), sizeof(double) * 3)
        .add(landmark.up.data(), sizeof(double) * 3)
        .add(landmark.sensor_origin.data(), sizeof(double) * 3);
    // The free space is derived from the capture scene, which the file does not hold: a capture
    // that carves it differently changes the results with the same points.
    for (const Eigen::Vector3f& c : landmark.empty_space.centres())
      hash.add(c.data(), sizeof(float) * 3);
  }
  return hash.hex();
}

}  // namespace lmk
