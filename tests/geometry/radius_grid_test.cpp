// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/radius_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "lmk/geometry/error.h"
#include "lmk/geometry/kdtree.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

std::vector<Index> sorted_indices(const std::vector<Neighbor>& neighbours) {
  std::vector<Index> out;
  for (const Neighbor& n : neighbours) out.push_back(n.index);
  std::sort(out.begin(), out.end());
  return out;
}

class RadiusGridTest : public ::testing::Test {
 protected:
  void SetUp() override {
    cloud_ = test::random_cloud(4000, 91);
    for (int i = 0; i < 4000; i += 89) cloud_.points[i] = Eigen::Vector3f::Constant(std::nanf(""));
    // Queries inside, at the edge of and outside the cloud, and some on its points exactly.
    queries_ = test::random_cloud(150, 92, 1.3f);
    for (int i = 0; i < 4000; i += 401) queries_.points.push_back(cloud_.points[i + 1]);
  }
  PointCloud cloud_, queries_;
};

// The voting relies on it: the same neighbour set as the k-d tree for every radius and cell,
// with the same squared distances, whatever the cell size against the radius.
TEST_F(RadiusGridTest, RadiusQueriesFindExactlyWhatTheKdTreeFinds) {
  const KdTree tree(cloud_);
  std::vector<Neighbor> found;
  for (const double cell : {0.05, 0.13, 0.4, 2.0}) {
    const RadiusGrid grid(cloud_, cell);
    EXPECT_EQ(grid.size(), cloud_.count_finite());
    for (const float radius : {0.0f, 0.02f, 0.1f, 0.25f, 0.7f}) {
      for (const auto& q : queries_.points) {
        grid.radius_unsorted(q, radius, found);
        const std::vector<Neighbor> truth = tree.radius(q, radius);
        ASSERT_EQ(sorted_indices(found), sorted_indices(truth))
            << "cell " << cell << " radius " << radius;
        std::sort(found.begin(), found.end(),
                  [](const Neighbor& a, const Neighbor& b) { return a.index < b.index; });
        std::vector<Neighbor> by_index = truth;
        std::sort(by_index.begin(), by_index.end(),
                  [](const Neighbor& a, const Neighbor& b) { return a.index < b.index; });
        for (std::size_t k = 0; k < found.size(); ++k) {
          EXPECT_EQ(found[k].squared_distance, by_index[k].squared_distance);
        }
      }
    }
  }
}

TEST_F(RadiusGridTest, NearestWithinIsTheNearestPointOrNothing) {
  const KdTree tree(cloud_);
  const RadiusGrid grid(cloud_, 0.1);
  for (const auto& q : queries_.points) {
    const std::optional<Neighbor> truth = tree.nearest(q);
    ASSERT_TRUE(truth);
    const float beyond = std::sqrt(truth->squared_distance) * 1.5f + 1e-4f;
    const std::optional<Neighbor> found = grid.nearest_within(q, beyond);
    ASSERT_TRUE(found);
    EXPECT_EQ(found->index, truth->index);
    EXPECT_EQ(found->squared_distance, truth->squared_distance);
    // Strictly closer than the radius: a radius of exactly the distance finds nothing.
    EXPECT_FALSE(grid.nearest_within(q, std::sqrt(truth->squared_distance) * 0.99f));
  }
}

TEST(RadiusGrid, EmptyCloudsNonFiniteQueriesAndBadCells) {
  const RadiusGrid empty(PointCloud{}, 0.1);
  std::vector<Neighbor> found{{1, 1.0f}};
  empty.radius_unsorted(Eigen::Vector3f::Zero(), 1.0f, found);
  EXPECT_TRUE(found.empty());
  const PointCloud cloud = test::random_cloud(100, 5);
  const RadiusGrid grid(cloud, 0.1);
  grid.radius_unsorted(Eigen::Vector3f::Constant(std::nanf("")), 1.0f, found);
  EXPECT_TRUE(found.empty());
  EXPECT_THROW(RadiusGrid(cloud, 0.0), Error);
  EXPECT_THROW(RadiusGrid(cloud, std::nan("")), Error);
}

}  // namespace
}  // namespace lmk
