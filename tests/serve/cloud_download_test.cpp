// SPDX-License-Identifier: BSD-3-Clause
// The cloud download is written a piece at a time (issue #34, finding 3): the pieces bound what the
// server holds, and together they are the one answer the page reads.
#include "lmk/serve/cloud_download.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>

namespace lmk::serve {
namespace {

Scene scene_of(std::size_t n, bool colours) {
  PointCloud c;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < n; ++i) {
    // Every third point is a hole, as an organised frame's are.
    c.points.emplace_back(i % 3 == 1 ? Eigen::Vector3f(nan, nan, nan)
                                     : Eigen::Vector3f(0.001f * i, -0.002f * i, 1.5f));
    if (colours) c.colors.push_back({static_cast<std::uint8_t>(i % 256), 7, 200});
  }
  return {"4", "frame.pcd", "file", std::make_shared<const PointCloud>(std::move(c))};
}

// The download's pieces, each at most `per_piece` points; their count in `pieces`.
nlohmann::json read_all(CloudDownload& d, std::size_t per_piece, std::size_t& pieces) {
  std::string text;
  pieces = 0;
  for (std::string piece = d.next(per_piece); !piece.empty(); piece = d.next(per_piece)) {
    // A piece of points holds at most per_piece of them: 3 numbers each.
    const auto numbers = static_cast<std::size_t>(std::count(piece.begin(), piece.end(), ',')) + 1;
    EXPECT_LE(numbers, 3 * per_piece + 8) << piece.substr(0, 80);
    text += piece;
    ++pieces;
  }
  return nlohmann::json::parse(text);
}

TEST(CloudDownload, ThePiecesMakeTheAnswerAndEachHoldsAFew) {
  const Scene s = scene_of(3000, true);
  CloudDownload d(s, 100000);
  std::size_t pieces = 0;
  const nlohmann::json j = read_all(d, 100, pieces);
  EXPECT_EQ(j["id"], "4");
  EXPECT_EQ(j["unit"], "mm");
  EXPECT_EQ(j["stride"], 1);
  EXPECT_EQ(j["points"], 2000);  // the holes are left out
  ASSERT_EQ(j["positions"].size(), 3u * 2000);
  ASSERT_EQ(j["colors"].size(), 3u * 2000);
  EXPECT_GE(pieces, 2u * 2000 / 100);  // the points came 100 at a time, positions then colours
  std::size_t k = 0;
  for (std::size_t i = 0; i < s.cloud->size(); ++i) {
    if (i % 3 == 1) continue;
    EXPECT_EQ(j["positions"][3 * k].get<long>(), std::lround(1000.0 * s.cloud->points[i].x()));
    EXPECT_EQ(j["positions"][3 * k + 2].get<long>(), 1500);
    EXPECT_EQ(j["colors"][3 * k].get<int>(), static_cast<int>(i % 256));
    ++k;
  }
}

TEST(CloudDownload, KeepsEveryKthPointWithinTheLimitAndSaysNullWithoutColour) {
  CloudDownload d(scene_of(3000, false), 700);
  std::size_t pieces = 0;
  const nlohmann::json j = read_all(d, 64, pieces);
  EXPECT_EQ(j["stride"], 3);  // 2000 finite points, at most 700 kept
  EXPECT_EQ(j["points"], 667);
  EXPECT_EQ(d.points(), 667u);
  EXPECT_EQ(j["positions"].size(), 3u * 667);
  EXPECT_TRUE(j["colors"].is_null());
}

TEST(CloudDownload, ACloudWithoutFinitePointsIsAnEmptyAnswer) {
  Scene s = scene_of(0, false);
  CloudDownload d(s, 10);
  std::size_t pieces = 0;
  const nlohmann::json j = read_all(d, 10, pieces);
  EXPECT_EQ(j["points"], 0);
  EXPECT_TRUE(j["positions"].empty());
}

}  // namespace
}  // namespace lmk::serve
