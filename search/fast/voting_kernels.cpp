// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/fast/voting_kernels.h"

// On x86-64 each kernel is also compiled for AVX2, eight lanes instead of SSE2's four, and the
// loader picks the build the processor runs (GCC's and Clang's function multiversioning). Without
// FMA in the list no multiply-add is fused, so both builds give the same values.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define LMK_VOTING_KERNEL __attribute__((target_clones("avx2", "default")))
#else
#define LMK_VOTING_KERNEL
#endif

namespace lmk::detail {

// The same arithmetic in the same order as the model's features (point_pair_voting.cpp), where
// Eigen sums a 3-vector's products as x + (y + z), so that a scene pair and the model pair it
// matches fall into the same key, bit for bit.
LMK_VOTING_KERNEL void pair_feature_keys(const PairQuantisation& q, const Eigen::Vector3f& nr,
                                         const Eigen::Matrix3f& Rs, NeighbourBlock& block) {
  const float step = q.distance_step;
  const auto bins = static_cast<float>(q.distance_bins);
  const int skip_coplanar = q.skip_coplanar ? 1 : 0;
  const std::uint32_t no_vote = q.no_vote_key;
  const float nrx = nr.x(), nry = nr.y(), nrz = nr.z();
  const float r10 = Rs(1, 0), r11 = Rs(1, 1), r12 = Rs(1, 2);
  const float r20 = Rs(2, 0), r21 = Rs(2, 1), r22 = Rs(2, 2);
  for (int i = 0; i < block.size; ++i) {
    const float dx = block.dx[i], dy = block.dy[i], dz = block.dz[i];
    const float nx = block.nx[i], ny = block.ny[i], nz = block.nz[i];
    const float distance = std::sqrt(dx * dx + (dy * dy + dz * dz));
    const float ux = dx / distance, uy = dy / distance, uz = dz / distance;
    const float c1 = nrx * ux + (nry * uy + nrz * uz);
    const float c2 = nx * ux + (ny * uy + nz * uz);
    const float c3 = nrx * nx + (nry * ny + nrz * nz);
    // Bitwise ands of ints, not && of bools: a short circuit is a branch, and a branch keeps the
    // loop scalar.
    const int coplanar = static_cast<int>(c3 > kCoplanarCos) &
                         static_cast<int>(std::abs(c1) < kCoplanarSin) &
                         static_cast<int>(std::abs(c2) < kCoplanarSin);
    const float distance_in_bins = distance / step;
    const bool votes = (static_cast<int>(distance > 1e-6f) & ((skip_coplanar & coplanar) ^ 1) &
                        static_cast<int>(distance_in_bins < bins)) != 0;
    // A lane that casts no vote goes on with zeros, so that no NaN reaches a conversion to int.
    const auto bin = [&](float c) {
      return static_cast<std::uint32_t>(
          std::min(static_cast<int>(fast_acos(votes ? c : 0.0f) / kAngleStep), kAngleBins - 1));
    };
    const auto db = static_cast<std::uint32_t>(static_cast<int>(votes ? distance_in_bins : 0.0f));
    const std::uint32_t key = pair_key(db, bin(c1), bin(c2), bin(c3));
    block.key[i] = votes ? key : no_vote;
    // (Rs d).z and .y, Eigen's order again.
    const float vy = r10 * dx + (r11 * dy + r12 * dz);
    const float vz = r20 * dx + (r21 * dy + r22 * dz);
    block.alpha[i] = fast_atan2(vz, vy) * kAlphaBinsPerRad;
  }
}

// Rotating the model pair by alpha = alpha_s - alpha_m about x aligns it with the scene's.
// Wrapped into [0, bins) by adding 0 or a full turn: the same sum as a conditional add, without
// a branch.
LMK_VOTING_KERNEL void vote_bins(float alpha_s, const std::uint32_t* first_vote,
                                 const float* alpha_m, std::uint32_t n, std::uint32_t* bins) {
  for (std::uint32_t e = 0; e < n; ++e) {
    float alpha = alpha_s - alpha_m[e];
    alpha += static_cast<float>(alpha < 0.0f) * static_cast<float>(kAlphaBins);
    bins[e] = first_vote[e] +
              static_cast<std::uint32_t>(std::min(static_cast<int>(alpha), kAlphaBins - 1));
  }
}

}  // namespace lmk::detail
