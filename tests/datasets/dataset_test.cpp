// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/datasets/dataset.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

namespace fs = std::filesystem;

// A small valid dataset on disk: two landmarks, two scenes; the files only need to exist.
class DatasetTest : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* f : {"bowl.lmk", "cup.lmk", "a.pcd", "b.pcd"})
      test::write_text(dir_.file(f), "x");
    dataset_.name = "tiny";
    dataset_.landmarks = {{"bowl", "bowl.lmk", Symmetry{Eigen::Vector3d::UnitZ()}},
                          {"cup", "cup.lmk", Symmetry{}}};
    DatasetScene a{"a", "a.pcd", "simple", pose_from_xyz_rpy({0, 0, 1.2}, {0.1, 0.2, 0.3}), {}, {}};
    a.pairs = {{"bowl", true, {pose_from_xyz_rpy({0.1, 0.2, 0.7}, {0, 0, 1})}, {}, {}},
               {"cup", true, {}, {}, {}}};
    DatasetScene b{"b", "b.pcd", "cluttered", Eigen::Isometry3d::Identity(), {}, {}};
    dataset_.scenes = {a, b};
  }

  // Writes dataset.json with `edit` applied to the valid JSON, and returns the load error.
  std::string error_after(const std::function<void(nlohmann::json&)>& edit) {
    save_dataset(dir_.path().string(), dataset_);
    nlohmann::json j;
    std::ifstream(dir_.file("dataset.json")) >> j;
    edit(j);
    test::write_text(dir_.file("dataset.json"), j.dump());
    try {
      load_dataset(dir_.path().string());
    } catch (const Error& e) {
      return e.what();
    }
    ADD_FAILURE() << "the dataset loaded";
    return "";
  }

  test::ScratchDir dir_;
  Dataset dataset_;
};

TEST_F(DatasetTest, RoundTrip) {
  save_dataset(dir_.path().string(), dataset_);
  const Dataset d = load_dataset(dir_.path().string());
  EXPECT_EQ(d.name, "tiny");
  ASSERT_EQ(d.landmarks.size(), 2u);
  EXPECT_TRUE(d.landmarks[0].symmetry.axis.has_value());
  EXPECT_FALSE(d.landmarks[1].symmetry.axis.has_value());
  ASSERT_EQ(d.scenes.size(), 2u);
  EXPECT_EQ(d.scenes[1].setting, "cluttered");
  EXPECT_TRUE(d.scenes[0].T_scene_sensor.isApprox(dataset_.scenes[0].T_scene_sensor, 1e-12));
  const DatasetPair bowl = d.pair(d.scenes[0], "bowl");
  ASSERT_EQ(bowl.instances.size(), 1u);
  EXPECT_TRUE(bowl.instances[0].isApprox(dataset_.scenes[0].pairs[0].instances[0], 1e-12));
  // A pair the scene does not list is out of context, without instances.
  const DatasetPair unlisted = d.pair(d.scenes[1], "bowl");
  EXPECT_FALSE(unlisted.in_context);
  EXPECT_TRUE(unlisted.instances.empty());
}

TEST_F(DatasetTest, ClearErrors) {
  const auto expect = [](const std::string& message, const std::string& part) {
    EXPECT_NE(message.find(part), std::string::npos) << message;
  };
  expect(error_after([](auto& j) { j["version"] = 9; }), "version: dataset format version 9");
  expect(error_after([](auto& j) { j["scenes"][1]["file"] = "gone.pcd"; }),
         "scenes[1].file: 'gone.pcd' does not exist");
  expect(error_after([](auto& j) { j["landmarks"][1]["file"] = "gone.lmk"; }),
         "landmarks[1].file: 'gone.lmk' does not exist");
  expect(error_after([](auto& j) { j["landmarks"][1]["name"] = "bowl"; }),
         "duplicate landmark name 'bowl'");
  expect(error_after([](auto& j) { j["scenes"][0]["pairs"][1]["landmark"] = "plate"; }),
         "scenes[0].pairs[1]: unknown landmark 'plate'");
  expect(error_after([](auto& j) {
           j["scenes"][0]["pairs"][0]["instances"][0]["quaternion"] = {2, 0, 0, 0};
         }),
         "scenes[0].pairs[0].instances[0].quaternion: is not a unit quaternion");
  expect(error_after([](auto& j) {
           j["scenes"][0]["sensor_pose"]["position"] = {0, 0};
         }),
         "scenes[0].sensor_pose.position: must be an array of 3 numbers");
  expect(error_after([](auto& j) { j["scenes"][1].erase("setting"); }),
         "scenes[1]: missing field 'setting'");
  test::write_text(dir_.file("dataset.json"), "{ not json");
  EXPECT_THROW(load_dataset(dir_.path().string()), Error);
  EXPECT_THROW(load_dataset(dir_.file("nowhere")), Error);
}

// Issue #34, finding 5: dataset.json read scene and landmark files outside its directory, a FIFO
// there was "does not exist", and a symbolic link loop was an internal error.
TEST_F(DatasetTest, FilesStayInsideTheDatasetDirectoryUnlessAllowed) {
  const auto expect = [](const std::string& message, const std::string& part) {
    EXPECT_NE(message.find(part), std::string::npos) << message;
  };
  // A file beside the dataset directory, reached three ways.
  const fs::path outside =
      dir_.path().parent_path() / (dir_.path().filename().string() + "-secret.pcd");
  test::write_text(outside.string(), "SECRET");
  fs::create_symlink(outside, dir_.path() / "link.pcd");
  const std::string up = "../" + outside.filename().string();
  for (const std::string& file : {up, outside.string(), std::string("link.pcd")}) {
    expect(error_after([&](auto& j) { j["scenes"][1]["file"] = file; }),
           "lies outside the dataset directory");
    // Allowed on request.
    EXPECT_NO_THROW(load_dataset(dir_.path().string(), DatasetFiles::anywhere)) << file;
  }
  // A link that stays inside is fine.
  fs::create_symlink("b.pcd", dir_.path() / "inside.pcd");
  dataset_.scenes[1].file = "inside.pcd";
  save_dataset(dir_.path().string(), dataset_);
  EXPECT_NO_THROW(load_dataset(dir_.path().string()));

  ASSERT_EQ(::mkfifo(dir_.file("pipe.pcd").c_str(), 0600), 0);
  expect(error_after([](auto& j) { j["scenes"][1]["file"] = "pipe.pcd"; }), "is a named pipe");
  fs::create_symlink("loop2.pcd", dir_.path() / "loop1.pcd");
  fs::create_symlink("loop1.pcd", dir_.path() / "loop2.pcd");
  expect(error_after([](auto& j) { j["scenes"][1]["file"] = "loop1.pcd"; }),
         "scenes[1].file: 'loop1.pcd'");
  fs::remove(outside);
}

TEST_F(DatasetTest, HiddenFractionsRoundTripAndAreChecked) {
  dataset_.scenes[0].pairs[0].hidden = {0.25};
  save_dataset(dir_.path().string(), dataset_);
  const Dataset d = load_dataset(dir_.path().string());
  EXPECT_EQ(d.pair(d.scenes[0], "bowl").hidden, std::vector<double>{0.25});
  EXPECT_TRUE(d.pair(d.scenes[0], "cup").hidden.empty());  // optional
  const auto expect = [](const std::string& message, const std::string& part) {
    EXPECT_NE(message.find(part), std::string::npos) << message;
  };
  expect(error_after([](auto& j) {
           j["scenes"][0]["pairs"][0]["hidden"] = {0.1, 0.2};
         }),
         "scenes[0].pairs[0].hidden: must be an array of one fraction per instance");
  expect(error_after([](auto& j) { j["scenes"][0]["pairs"][0]["hidden"] = {1.5}; }),
         "scenes[0].pairs[0].hidden[0]: must be a fraction in [0, 1]");
  dataset_.scenes[0].pairs[0].hidden = {0.1, 0.2};
  EXPECT_THROW(save_dataset(dir_.path().string(), dataset_), Error);
}

TEST_F(DatasetTest, SaveRefusesAnInconsistentDataset) {
  dataset_.scenes[0].pairs[0].landmark = "plate";
  EXPECT_THROW(save_dataset(dir_.path().string(), dataset_), Error);
  EXPECT_FALSE(std::filesystem::exists(dir_.file("dataset.json")));
}

}  // namespace
}  // namespace lmk
