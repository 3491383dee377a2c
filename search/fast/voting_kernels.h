// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The voting's inner loops (point_pair_voting.h), written lane by lane without a branch: the
// quantised point pair feature of a reference scene point with each of a block of its neighbours,
// and the accumulator bins a scene pair votes for. Internal.
//
// GCC and Clang turn these loops into vector instructions, four or eight lanes at once, because
// voting_kernels.cpp is compiled with -fno-math-errno and -fno-trapping-math
// (search/CMakeLists.txt): without them the compilers keep a branch for sqrt's errno and will not
// if-convert a division or a conversion to int, and the loops stay scalar. Neither option changes
// a value: both only let the compiler assume that no one reads errno or traps on a floating-point
// exception. The model's own features use the same functions, one pair at a time.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "lmk/search/fast/point_pair_voting.h"

namespace lmk::detail {

inline constexpr float kPairPi = 3.14159265358979f;
inline constexpr int kAngleBins = 15;
inline constexpr float kAngleStep = kPairPi / kAngleBins;  // 12 degrees, as Drost et al.
inline constexpr int kAlphaBins = 30;                      // rotations about the normal
inline constexpr float kAlphaBinsPerRad = kAlphaBins / (2.0f * kPairPi);

/// The coplanarity test in cosines, so that the voting can tell a coplanar pair before any arc
/// cosine: both normals within kCoplanarAngle of each other and of perpendicular to d.
inline const float kCoplanarCos = std::cos(static_cast<float>(kCoplanarAngle));
inline const float kCoplanarSin = std::sin(static_cast<float>(kCoplanarAngle));

/// acos to about 7e-5 rad (Abramowitz & Stegun 4.4.45): the voting calls it three times per scene
/// pair, and the bins are 12 degrees wide.
inline float fast_acos(float x) {
  x = std::clamp(x, -1.0f, 1.0f);
  const float a = std::abs(x);
  const float r =
      std::sqrt(1.0f - a) * (1.5707288f + a * (-0.2121144f + a * (0.0742610f + a * -0.0187293f)));
  return x >= 0.0f ? r : kPairPi - r;
}

/// atan2 to about 1e-4 rad (a minimax polynomial of atan on [0, 1] and octant symmetry); 0 at the
/// origin, where t below is 0.
inline float fast_atan2(float y, float x) {
  const float ax = std::abs(x), ay = std::abs(y);
  const float big = std::max(ax, ay);
  const float t = big == 0.0f ? 0.0f : std::min(ax, ay) / big, t2 = t * t;
  float r =
      t *
      (0.99997726f +
       t2 * (-0.33262347f +
             t2 * (0.19354346f + t2 * (-0.11643287f + t2 * (0.05265332f + t2 * -0.01172120f)))));
  r = ay > ax ? 0.5f * kPairPi - r : r;
  r = x < 0.0f ? kPairPi - r : r;
  return y < 0.0f ? -r : r;
}

/// The key of a feature's four bins, the model's table and the scene's lookups alike.
inline std::uint32_t pair_key(std::uint32_t distance_bin, std::uint32_t a1, std::uint32_t a2,
                              std::uint32_t a3) {
  return ((distance_bin * kAngleBins + a1) * kAngleBins + a2) * kAngleBins + a3;
}

/// A block of a reference point's neighbours as a structure of arrays: the segment d from the
/// reference point to each, and each one's normal; `pair_feature_keys` fills `key` and `alpha`.
struct NeighbourBlock {
  static constexpr int kCapacity = 64;
  alignas(64) float dx[kCapacity], dy[kCapacity], dz[kCapacity];
  alignas(64) float nx[kCapacity], ny[kCapacity], nz[kCapacity];
  alignas(64) std::uint32_t key[kCapacity];
  alignas(64) float alpha[kCapacity];  ///< the angle of d about the normal, in alpha bins
  int size = 0;
};

/// How a model quantises the features, and the key it keeps for a pair that casts no vote.
struct PairQuantisation {
  float distance_step = 0.0f;
  int distance_bins = 0;
  bool skip_coplanar = false;
  std::uint32_t no_vote_key = 0;  ///< a key no model pair has
};

/// For each neighbour in `block` of the reference point (normal `nr`; `Rs` takes it onto +x):
/// the key of the feature F(reference, neighbour), or `q.no_vote_key` for a pair that casts no
/// vote (coincident points, a coplanar pair the model left out, a pair longer than the model);
/// and the angle of d about +x once rotated by Rs, in alpha bins. The key is `pair_key`'s.
void pair_feature_keys(const PairQuantisation& q, const Eigen::Vector3f& nr,
                       const Eigen::Matrix3f& Rs, NeighbourBlock& block);

/// The accumulator bin each of `n` model pairs votes for when a scene pair at angle `alpha_s`
/// matches it: first_vote[e] (its model point's first bin) plus the bin of alpha_s - alpha_m[e]
/// (both in alpha bins), wrapped into [0, kAlphaBins).
void vote_bins(float alpha_s, const std::uint32_t* first_vote, const float* alpha_m,
               std::uint32_t n, std::uint32_t* bins);

}  // namespace lmk::detail
