// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/kdtree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <thread>

#include "tests/support/test_support.h"

namespace lmk {
namespace {

std::vector<float> brute_force_sorted_d2(const PointCloud& cloud, const Eigen::Vector3f& q) {
  std::vector<float> d2;
  for (const auto& p : cloud.points) {
    if (is_finite(p)) d2.push_back((p - q).squaredNorm());
  }
  std::sort(d2.begin(), d2.end());
  return d2;
}

class KdTreeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    cloud_ = test::random_cloud(5000, 77);
    for (int i = 0; i < 5000; i += 97) cloud_.points[i] = Eigen::Vector3f::Constant(std::nanf(""));
    queries_ = test::random_cloud(200, 78, 1.2f);
  }
  PointCloud cloud_, queries_;
};

TEST_F(KdTreeTest, KnnEqualsBruteForce) {
  const KdTree tree(cloud_);
  EXPECT_EQ(tree.size(), cloud_.count_finite());
  for (const auto& q : queries_.points) {
    const std::vector<float> truth = brute_force_sorted_d2(cloud_, q);
    const std::vector<Neighbor> found = tree.knn(q, 10);
    ASSERT_EQ(found.size(), 10u);
    for (std::size_t i = 0; i < found.size(); ++i) {
      EXPECT_FLOAT_EQ(found[i].squared_distance, truth[i]);
      // The reported index really is at the reported distance.
      EXPECT_FLOAT_EQ((cloud_.points[found[i].index] - q).squaredNorm(), found[i].squared_distance);
    }
  }
}

TEST_F(KdTreeTest, RadiusEqualsBruteForce) {
  const KdTree tree(cloud_);
  const float r = 0.15f;
  for (const auto& q : queries_.points) {
    std::vector<Index> truth;
    for (Index i = 0; i < cloud_.size(); ++i) {
      if (is_finite(cloud_.points[i]) && (cloud_.points[i] - q).squaredNorm() < r * r) {
        truth.push_back(i);
      }
    }
    const std::vector<Neighbor> found = tree.radius(q, r);
    std::vector<Index> got;
    for (const Neighbor& n : found) got.push_back(n.index);
    EXPECT_TRUE(std::is_sorted(found.begin(), found.end(), [](const auto& a, const auto& b) {
      return a.squared_distance < b.squared_distance;
    }));
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, truth);
  }
}

TEST_F(KdTreeTest, ConcurrentQueriesMatchSerialOnes) {
  const KdTree tree(cloud_);
  std::vector<Index> serial(queries_.size());
  for (std::size_t i = 0; i < queries_.size(); ++i)
    serial[i] = tree.nearest(queries_.points[i])->index;
  std::vector<std::vector<Index>> parallel(4, std::vector<Index>(queries_.size()));
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int round = 0; round < 20; ++round) {
        for (std::size_t i = 0; i < queries_.size(); ++i) {
          parallel[t][i] = tree.knn(queries_.points[i], 3).front().index;
        }
      }
    });
  }
  for (auto& th : threads) th.join();
  for (const auto& result : parallel) EXPECT_EQ(result, serial);
}

TEST(KdTree, EmptyAndSmallClouds) {
  const KdTree empty{PointCloud()};
  EXPECT_FALSE(empty.nearest({0, 0, 0}).has_value());
  EXPECT_TRUE(empty.knn({0, 0, 0}, 5).empty());
  EXPECT_TRUE(empty.radius({0, 0, 0}, 1.0f).empty());
  const KdTree two{PointCloud({{0, 0, 0}, {1, 0, 0}})};
  EXPECT_EQ(two.knn({0.9f, 0, 0}, 5).size(), 2u);
  EXPECT_EQ(two.knn({0.9f, 0, 0}, 5).front().index, 1u);
}

TEST(KdTree, SurvivesTheCloudAndAMove) {
  auto cloud = std::make_unique<PointCloud>(test::random_cloud(100, 5));
  const Eigen::Vector3f target = cloud->points[42];
  KdTree tree(*cloud);
  cloud.reset();
  const KdTree moved = std::move(tree);
  EXPECT_EQ(moved.nearest(target)->index, 42u);
}

}  // namespace
}  // namespace lmk
