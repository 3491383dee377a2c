// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/filters.h"

#include <gtest/gtest.h>

#include <set>

#include "tests/support/test_support.h"

namespace lmk {
namespace {

TEST(RemoveNonFinite, KeepsExactlyTheFinitePointsWithTheirAttributes) {
  PointCloud cloud = test::random_cloud(100, 3);
  cloud.labels.resize(100);
  for (int i = 0; i < 100; ++i) cloud.labels[i] = i;
  cloud.points[5].x() = std::nanf("");
  cloud.points[17].z() = std::numeric_limits<float>::infinity();
  cloud.width = 10;
  cloud.height = 10;
  const PointCloud out = remove_non_finite(cloud);
  ASSERT_EQ(out.size(), 98u);
  EXPECT_EQ(out.count_finite(), 98u);
  EXPECT_FALSE(out.is_organized());
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_EQ(out.points[i], cloud.points[out.labels[i]]);  // the label is the source index
  }
}

TEST(RandomSample, IsDistinctSortedInRangeAndDeterministic) {
  const Indices a = random_sample_indices(10000, 500, 42);
  ASSERT_EQ(a.size(), 500u);
  EXPECT_TRUE(std::is_sorted(a.begin(), a.end()));
  EXPECT_EQ(std::set<Index>(a.begin(), a.end()).size(), 500u);
  EXPECT_LT(a.back(), 10000u);
  EXPECT_EQ(a, random_sample_indices(10000, 500, 42));
  EXPECT_NE(a, random_sample_indices(10000, 500, 43));
}

TEST(RandomSample, CountAtLeastNReturnsEverything) {
  EXPECT_EQ(random_sample_indices(5, 9, 1), (Indices{0, 1, 2, 3, 4}));
  EXPECT_TRUE(random_sample_indices(0, 3, 1).empty());
}

TEST(RandomSample, IsUniform) {
  // Each of 10 indices drawn 3 at a time should come up 30% of the time.
  std::vector<int> hits(10, 0);
  const int trials = 20000;
  for (int t = 0; t < trials; ++t) {
    for (Index i : random_sample_indices(10, 3, static_cast<std::uint64_t>(t))) ++hits[i];
  }
  for (int h : hits) EXPECT_NEAR(static_cast<double>(h) / trials, 0.3, 0.015);
}

TEST(RandomSample, CloudVersionDrawsOnlyFinitePoints) {
  PointCloud cloud = test::random_cloud(50, 9);
  for (int i = 0; i < 50; i += 2) cloud.points[i] = Eigen::Vector3f::Constant(std::nanf(""));
  const PointCloud sample = random_sample(cloud, 100, 1);
  EXPECT_EQ(sample.size(), 25u);
  EXPECT_EQ(sample.count_finite(), 25u);
}

}  // namespace
}  // namespace lmk
