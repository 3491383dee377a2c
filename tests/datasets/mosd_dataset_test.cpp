// SPDX-License-Identifier: BSD-3-Clause
// The real-data dataset from mOSD's labelled frames: landmarks around the labelled objects, and
// ground truth that puts each landmark back on its object in the moved copies.

#include "lmk/datasets/mosd_dataset.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/kdtree.h"
#include "lmk/landmark/landmark_file.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

TEST(MosdDataset, GroundTruthPutsEachLandmarkOnItsObjectInTheMovedCopies) {
  LMK_REQUIRE_SHARED_DATA(data);
  test::ScratchDir out;
  MosdOptions options;
  options.max_frames = 2;
  const Dataset d =
      generate_mosd_dataset((data / "mosd" / "learn").string(), out.path().string(), options);
  ASSERT_FALSE(d.landmarks.empty());
  EXPECT_EQ(d.scenes.size(), 4u);  // two frames, two copies each
  std::size_t checked = 0;
  for (const DatasetScene& scene : d.scenes) {
    const PointCloud cloud = read_cloud((out.path() / scene.file).string());
    const KdTree tree(cloud);
    for (const DatasetPair& pair : scene.pairs) {
      ASSERT_EQ(pair.instances.size(), 1u);
      EXPECT_TRUE(pair.in_context);
      const Landmark l =
          load_landmark((out.path() / ("landmarks/" + pair.landmark + ".lmk")).string());
      const Eigen::Isometry3d T = pair.instances[0] * l.box.pose.inverse();
      // The moved copy was not captured from: its sensor pose moved, and the motion is no identity.
      EXPECT_GT((T.translation()).norm() + std::abs(Eigen::AngleAxisd(T.linear()).angle()), 0.05);
      double sum = 0.0;
      for (const auto& p : l.points.points) {
        const auto n = tree.nearest((T * p.cast<double>()).cast<float>());
        ASSERT_TRUE(n.has_value());
        sum += std::sqrt(static_cast<double>(n->squared_distance));
      }
      // The landmark's points are 5 mm voxel centroids of the frame's own points.
      EXPECT_LT(sum / l.points.size(), 0.003) << scene.name << " " << pair.landmark;
      ++checked;
    }
  }
  EXPECT_GT(checked, 0u);
  EXPECT_NO_THROW(load_dataset(out.path().string()));
}

TEST(MosdDataset, AMissingDirectoryIsAClearError) {
  test::ScratchDir out;
  try {
    generate_mosd_dataset(out.file("nowhere"), out.file("ds"));
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("learnN.pcd"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lmk
