// SPDX-License-Identifier: BSD-3-Clause
// The voting's vectorised inner loops (search/fast/voting_kernels.h): each scene pair must land
// in the key and the alpha bin the scalar feature gives it, or its votes go astray; and the
// voting as a whole must still find a model's own pose.
#include "lmk/search/fast/voting_kernels.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "lmk/geometry/radius_grid.h"
#include "lmk/search/fast/point_pair_voting.h"

namespace lmk {
namespace {

using detail::NeighbourBlock;
using detail::PairQuantisation;

constexpr float kStep = 0.01f;
constexpr int kDistanceBins = 12;

Eigen::Vector3f random_unit(std::mt19937& rng) {
  std::normal_distribution<float> n;
  return Eigen::Vector3f(n(rng), n(rng), n(rng)).normalized();
}

// The key of F(0 -> d) with the reference normal nr, one pair at a time with Eigen, as the model
// computes its own pairs' features; -1 for a pair that casts no vote.
long scalar_key(const PairQuantisation& q, const Eigen::Vector3f& nr, const Eigen::Vector3f& d,
                const Eigen::Vector3f& n) {
  const float distance = d.norm();
  if (!(distance > 1e-6f)) return -1;
  const Eigen::Vector3f u = d / distance;
  const float c[3] = {nr.dot(u), n.dot(u), nr.dot(n)};
  const bool coplanar = c[2] > detail::kCoplanarCos && std::abs(c[0]) < detail::kCoplanarSin &&
                        std::abs(c[1]) < detail::kCoplanarSin;
  const int db = static_cast<int>(distance / q.distance_step);
  if ((q.skip_coplanar && coplanar) || db >= q.distance_bins) return -1;
  long key = db;
  for (float ci : c) {
    key = key * detail::kAngleBins +
          std::min(static_cast<int>(detail::fast_acos(ci) / detail::kAngleStep),
                   detail::kAngleBins - 1);
  }
  return key;
}

// A block of `size` neighbours: random segments up to 1.5 model lengths, with some coincident
// points and some pairs coplanar with the reference point (on its tangent plane, same normal).
NeighbourBlock random_block(std::mt19937& rng, const Eigen::Vector3f& nr, int size) {
  NeighbourBlock block;
  std::uniform_real_distribution<float> length(0.0f, 1.5f * kStep * kDistanceBins);
  for (int i = 0; i < size; ++i) {
    Eigen::Vector3f d = random_unit(rng) * length(rng);
    Eigen::Vector3f n = random_unit(rng);
    if (i % 7 == 3) d.setZero();
    if (i % 5 == 1) {
      d -= nr * nr.dot(d);
      n = nr;
    }
    block.dx[i] = d.x(), block.dy[i] = d.y(), block.dz[i] = d.z();
    block.nx[i] = n.x(), block.ny[i] = n.y(), block.nz[i] = n.z();
  }
  block.size = size;
  return block;
}

TEST(VotingKernels, EachPairGetsTheKeyAndAngleOfTheScalarFeature) {
  std::mt19937 rng(7);
  const std::uint32_t no_vote = kDistanceBins * 15 * 15 * 15;
  std::size_t voting = 0, silent = 0;
  for (const bool skip_coplanar : {false, true}) {
    const PairQuantisation q{kStep, kDistanceBins, skip_coplanar, no_vote};
    for (int size = 1; size <= NeighbourBlock::kCapacity; ++size) {
      const Eigen::Vector3f nr = random_unit(rng);
      const Eigen::Matrix3f Rs =
          Eigen::Quaternionf::FromTwoVectors(nr, Eigen::Vector3f::UnitX()).toRotationMatrix();
      NeighbourBlock block = random_block(rng, nr, size);
      detail::pair_feature_keys(q, nr, Rs, block);
      for (int i = 0; i < size; ++i) {
        const Eigen::Vector3f d(block.dx[i], block.dy[i], block.dz[i]);
        const Eigen::Vector3f n(block.nx[i], block.ny[i], block.nz[i]);
        const long expected = scalar_key(q, nr, d, n);
        if (expected < 0) {
          EXPECT_EQ(block.key[i], no_vote) << "lane " << i << " of " << size;
          ++silent;
        } else {
          EXPECT_EQ(block.key[i], static_cast<std::uint32_t>(expected))
              << "lane " << i << " of " << size;
          ++voting;
        }
        const Eigen::Vector3f v = Rs * d;
        EXPECT_EQ(block.alpha[i], detail::fast_atan2(v.z(), v.y()) * detail::kAlphaBinsPerRad);
      }
    }
  }
  // Both kinds of lane were exercised, skipped coplanar pairs among the silent ones.
  EXPECT_GT(voting, 1000u);
  EXPECT_GT(silent, 500u);
}

TEST(VotingKernels, VotesFallIntoTheirModelPointsAlphaBins) {
  std::mt19937 rng(11);
  const float half_turn = 0.5f * detail::kAlphaBins;
  std::uniform_real_distribution<float> angle(-half_turn, half_turn);
  std::vector<std::uint32_t> first(1000), bins(1000);
  std::vector<float> alpha_m(1000);
  for (std::size_t e = 0; e < first.size(); ++e) {
    first[e] = static_cast<std::uint32_t>(e) * detail::kAlphaBins;
    alpha_m[e] = angle(rng);
  }
  alpha_m[0] = half_turn;  // alpha_s - alpha_m at either end of a full turn
  alpha_m[1] = -half_turn;
  for (const float alpha_s : {-half_turn, -3.7f, 0.0f, 0.49f, 14.99f, half_turn}) {
    // Every count of model pairs, so that the vector loop's remainders are run too.
    for (std::uint32_t n : {1u, 3u, 4u, 5u, 17u, 1000u}) {
      detail::vote_bins(alpha_s, first.data(), alpha_m.data(), n, bins.data());
      for (std::uint32_t e = 0; e < n; ++e) {
        ASSERT_GE(bins[e], first[e]);
        ASSERT_LT(bins[e], first[e] + detail::kAlphaBins);
        float turn = alpha_s - alpha_m[e];
        if (turn < 0.0f) turn += detail::kAlphaBins;
        EXPECT_EQ(bins[e] - first[e],
                  std::min(static_cast<std::uint32_t>(turn), std::uint32_t{29}));
      }
    }
  }
}

TEST(VotingKernels, FastAtan2IsWithinItsStatedErrorEverywhere) {
  EXPECT_EQ(detail::fast_atan2(0.0f, 0.0f), 0.0f);
  for (int i = 0; i < 3600; ++i) {
    const double a = i * 2.0 * M_PI / 3600.0;
    for (const double r : {1e-6, 1.0, 1e6}) {
      const auto y = static_cast<float>(r * std::sin(a)), x = static_cast<float>(r * std::cos(a));
      EXPECT_NEAR(detail::fast_atan2(y, x), std::atan2(y, x), 1.5e-4) << y << ", " << x;
    }
  }
}

// Points on an ellipsoid with three different axes, with their normals.
PointCloud ellipsoid(int count) {
  std::mt19937 rng(3);
  const Eigen::Vector3f axes(0.06f, 0.04f, 0.025f);
  PointCloud cloud;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3f u = random_unit(rng);
    cloud.points.push_back(u.cwiseProduct(axes));
    cloud.normals.push_back(u.cwiseQuotient(axes).normalized());
  }
  return cloud;
}

TEST(PointPairVoting, AModelsBestVotedPoseLaysItOntoItsMovedSelf) {
  const PointCloud model = ellipsoid(400);
  const detail::PointPairModel pairs(model, 0.01, 0.13);
  const Eigen::Isometry3f T = Eigen::Translation3f(0.3f, -0.1f, 0.8f) *
                              Eigen::AngleAxisf(1.1f, Eigen::Vector3f(1, 2, 3).normalized());
  PointCloud scene;
  for (std::size_t i = 0; i < model.size(); ++i) {
    scene.points.push_back(T * model.points[i]);
    scene.normals.push_back(T.linear() * model.normals[i]);
  }
  const RadiusGrid grid(scene, 0.5 * pairs.diameter());
  std::vector<detail::PoseVote> votes;
  for (const Index reference : {Index{0}, Index{57}, Index{311}}) {
    pairs.vote(scene, grid, reference, 3, 0.75, votes);
    ASSERT_FALSE(votes.empty());
    // The best pose puts every model point within a few millimetres of the scene's surface: the
    // pose, or one of the ellipsoid's symmetric ones, to within the 12-degree alpha bins.
    const Eigen::Isometry3f best = votes.front().T_scene_model.cast<float>();
    double sum = 0.0;
    for (const Eigen::Vector3f& p : model.points) {
      float nearest = std::numeric_limits<float>::infinity();
      for (const Eigen::Vector3f& s : scene.points)
        nearest = std::min(nearest, (best * p - s).norm());
      sum += nearest;
    }
    EXPECT_LT(sum / model.size(), 0.006) << "reference " << reference;
  }
}

}  // namespace
}  // namespace lmk
