// SPDX-License-Identifier: BSD-3-Clause
// LandmarkLibrary: names confined to the directory, landmarks and their search indexes kept until
// their file changes.

#include "lmk/search/landmark_library.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <thread>

#include "lmk/geometry/error.h"
#include "tests/landmark/l_shape_scene.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

using namespace test_scenes;
using test::error_of;
using test::ScratchDir;

Landmark captured(const std::string& name, double margin) {
  static const PointCloud scene = render_scene(kCopies, false);
  Box box = box_at(kCopies[0]);
  box.size += Eigen::Vector3d::Constant(margin);
  return capture(scene, box, name);
}

TEST(LandmarkLibrary, KeepsEachIndexUntilTheFileOrTheSearchChanges) {
  const ScratchDir dir;
  const LandmarkLibrary library(dir.path());
  library.save(captured("block", 0.0), false);
  const FindSettings s;
  const std::shared_ptr<const LandmarkIndex> first = library.index("block", s);
  EXPECT_EQ(library.index("block", s), first);  // built once
  EXPECT_EQ(&first->landmark(), library.load("block").get());
  EXPECT_TRUE(first->suits(s));

  FindSettings coarser = s;
  coarser.scene.coarse_leaf = 0.015;
  const std::shared_ptr<const LandmarkIndex> other = library.index("block", coarser);
  EXPECT_NE(other, first);
  EXPECT_TRUE(other->suits(coarser));
  EXPECT_FALSE(other->suits(s));

  // A new file (another size, so that a coarse file clock cannot hide it) gives a new landmark and
  // a new index of it; the old index stays valid for whoever holds it.
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const Landmark bigger = captured("block", 0.02);
  library.save(bigger, true);
  const std::shared_ptr<const LandmarkIndex> after = library.index("block", s);
  EXPECT_NE(after, first);
  EXPECT_EQ(after->landmark().box.size, library.load("block")->box.size);
  EXPECT_NE(after->landmark().box.size, first->landmark().box.size);
  EXPECT_GT(first->landmark().points.size(), 0u);
  EXPECT_TRUE(first->suits(s));
}

TEST(LandmarkLibrary, IndexRefusesBadNamesAndMissingLandmarks) {
  const ScratchDir dir;
  const LandmarkLibrary library(dir.path());
  library.save(captured("block", 0.0), false);
  EXPECT_NE(error_of([&] { library.index("nothing", FindSettings()); }).find("it holds block"),
            std::string::npos);
  EXPECT_THROW(library.index("../block", FindSettings()), Error);
  FindSettings bad;
  bad.method = static_cast<SearchMethod>(7);  // a value without a name
  EXPECT_THROW(library.index("block", bad), Error);
}

}  // namespace
}  // namespace lmk
