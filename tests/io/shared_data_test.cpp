// SPDX-License-Identifier: BSD-3-Clause
// Every real PCD under ../shared/data loads and agrees with its own header. Skips when the data is
// absent (a fresh machine without ../shared).

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "lmk/geometry/cloud_io.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

namespace fs = std::filesystem;

// The header's WIDTH, HEIGHT and POINTS, parsed independently of PCL.
struct HeaderCounts {
  long long width = -1, height = -1, points = -1;
};

HeaderCounts header_counts(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  HeaderCounts h;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "WIDTH") words >> h.width;
    if (key == "HEIGHT") words >> h.height;
    if (key == "POINTS") words >> h.points;
    if (key == "DATA") break;
  }
  return h;
}

TEST(SharedData, EveryRealPcdLoadsAndAgreesWithItsHeader) {
  LMK_REQUIRE_SHARED_DATA(data);
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(data)) {
    if (entry.path().extension() != ".pcd") continue;
    SCOPED_TRACE(entry.path().string());
    const HeaderCounts h = header_counts(entry.path());
    const CloudFile file = read_cloud_file(entry.path().string());
    EXPECT_EQ(static_cast<long long>(file.cloud.size()), h.points);
    EXPECT_EQ(static_cast<long long>(file.cloud.width), h.width);
    EXPECT_EQ(static_cast<long long>(file.cloud.height), h.height);
    EXPECT_GT(file.cloud.count_finite(), 0u);
    ++files;
  }
  EXPECT_GT(files, 0);
}

TEST(SharedData, MilkSceneCounts) {
  LMK_REQUIRE_SHARED_DATA(data);
  const CloudFile file = read_cloud_file((data / "pcl/milk_cartoon_all_small_clorox.pcd").string());
  EXPECT_EQ(file.cloud.size(), 307200u);
  EXPECT_EQ(file.cloud.count_finite(), 241407u);
  EXPECT_EQ(file.cloud.width, 640u);
  EXPECT_EQ(file.cloud.height, 480u);
  EXPECT_TRUE(file.cloud.has_colors());
}

TEST(SharedData, MosdLabelsAreRead) {
  LMK_REQUIRE_SHARED_DATA(data);
  const CloudFile file = read_cloud_file((data / "mosd/learn/learn0.pcd").string());
  ASSERT_TRUE(file.cloud.has_labels());
  // Label 0 marks the NaN points (the dataset's README); the others are table or objects.
  for (std::size_t i = 0; i < file.cloud.size(); ++i) {
    if (file.cloud.labels[i] != 0) {
      EXPECT_TRUE(is_finite(file.cloud.points[i]));
    }
  }
}

}  // namespace
}  // namespace lmk
