// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/fast/point_pair_voting.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "lmk/geometry/error.h"
#include "lmk/search/fast/voting_kernels.h"

namespace lmk::detail {
namespace {

constexpr std::uint32_t kScanBlock = 64;  // accumulator bins per block of the best-pose scan

// The rotation taking `n` onto +x, and the angle of a point about +x once so rotated.
Eigen::Matrix3f rotation_to_x(const Eigen::Vector3f& n) {
  return Eigen::Quaternionf::FromTwoVectors(n, Eigen::Vector3f::UnitX()).toRotationMatrix();
}
float angle_about_x(const Eigen::Matrix3f& R, const Eigen::Vector3f& d) {
  const Eigen::Vector3f v = R * d;
  return fast_atan2(v.z(), v.y());
}

// Rx(alpha) at the centre of each alpha bin, computed once: the poses of every seed use them.
const std::array<Eigen::Matrix3f, kAlphaBins>& alpha_rotations() {
  static const std::array<Eigen::Matrix3f, kAlphaBins> rotations = [] {
    std::array<Eigen::Matrix3f, kAlphaBins> out;
    for (int b = 0; b < kAlphaBins; ++b) {
      const float alpha = (static_cast<float>(b) + 0.5f) / kAlphaBinsPerRad;
      out[b] = Eigen::AngleAxisf(alpha, Eigen::Vector3f::UnitX()).toRotationMatrix();
    }
    return out;
  }();
  return rotations;
}

struct Feature {
  float distance, a1, a2, a3;
  bool coplanar;
};

// F(p1, p2) of a model pair; false for coincident points. The scene's pairs are keyed by
// pair_feature_keys (voting_kernels.h), which must do the same arithmetic in the same order.
bool feature(const Eigen::Vector3f& p1, const Eigen::Vector3f& n1, const Eigen::Vector3f& p2,
             const Eigen::Vector3f& n2, Feature& f) {
  const Eigen::Vector3f d = p2 - p1;
  f.distance = d.norm();
  if (!(f.distance > 1e-6f)) return false;
  const Eigen::Vector3f u = d / f.distance;
  const float c[3] = {n1.dot(u), n2.dot(u), n1.dot(n2)};
  f.coplanar =
      c[2] > kCoplanarCos && std::abs(c[0]) < kCoplanarSin && std::abs(c[1]) < kCoplanarSin;
  f.a1 = fast_acos(c[0]);
  f.a2 = fast_acos(c[1]);
  f.a3 = fast_acos(c[2]);
  return true;
}

// The keys a model pair is hashed into, its feature's four quantities given in bins: the bin of
// each quantity and, near a bin edge, its neighbour too, so that noise in the scene's normals does
// not lose the vote. Bins outside the key space are left out.
template <class Visit>
void for_each_spread_key(const float bins[4], int distance_bins, Visit&& visit) {
  int lo[4], hi[4];
  for (int k = 0; k < 4; ++k) {
    const int b = static_cast<int>(std::floor(bins[k]));
    const float frac = bins[k] - static_cast<float>(b);
    lo[k] = frac < 0.25f ? b - 1 : b;
    hi[k] = frac > 0.75f ? b + 1 : b;
  }
  const auto in_range = [](int b, int count) { return b >= 0 && b < count; };
  for (int b0 = lo[0]; b0 <= hi[0]; ++b0)
    for (int b1 = lo[1]; b1 <= hi[1]; ++b1)
      for (int b2 = lo[2]; b2 <= hi[2]; ++b2)
        for (int b3 = lo[3]; b3 <= hi[3]; ++b3) {
          if (in_range(b0, distance_bins) && in_range(b1, kAngleBins) && in_range(b2, kAngleBins) &&
              in_range(b3, kAngleBins)) {
            visit(pair_key(static_cast<std::uint32_t>(b0), static_cast<std::uint32_t>(b1),
                           static_cast<std::uint32_t>(b2), static_cast<std::uint32_t>(b3)));
          }
        }
}

}  // namespace

PointPairModel::PointPairModel(const PointCloud& model, double distance_step, double diameter)
    : distance_step_(distance_step), diameter_(diameter) {
  if (!model.has_normals()) throw Error("point pair model: the model needs normals");
  if (!(distance_step > 0.0) || !(diameter > distance_step) || diameter / distance_step > 1000) {
    throw Error("point pair model: the diameter must exceed a positive distance step");
  }
  distance_bins_ = static_cast<int>(std::ceil(diameter / distance_step)) + 2;
  std::vector<Eigen::Vector3f> normals;
  for (std::size_t i = 0; i < model.size(); ++i) {
    if (!model.points[i].allFinite() || !model.normals[i].allFinite()) continue;
    points_.push_back(model.points[i]);
    normals.push_back(model.normals[i]);
    to_x_axis_.push_back(rotation_to_x(model.normals[i]));
  }

  // Every ordered pair within the diameter. A first pass counts the coplanar ones: a landmark with
  // relief keeps its non-coplanar pairs only, if they are a fifth or more.
  const auto for_each_pair = [&](auto&& visit) {
    for (std::size_t i = 0; i < points_.size(); ++i) {
      for (std::size_t j = 0; j < points_.size(); ++j) {
        Feature f;
        if (i == j || !feature(points_[i], normals[i], points_[j], normals[j], f)) continue;
        if (f.distance <= diameter) visit(i, j, f);
      }
    }
  };
  std::size_t total = 0, coplanar = 0;
  for_each_pair([&](std::size_t, std::size_t, const Feature& f) {
    ++total;
    coplanar += f.coplanar ? 1 : 0;
  });
  skip_coplanar_ = total > 0 && (total - coplanar) * 5 >= total;

  struct Keyed {
    std::uint32_t key, first_vote;
    float alpha_in_bins;
  };
  std::vector<Keyed> keyed;
  keyed.reserve(4 * total);  // about 1.5^4 bins per pair with the edge spreading below
  const float step = static_cast<float>(distance_step);
  for_each_pair([&](std::size_t i, std::size_t j, const Feature& f) {
    if (skip_coplanar_ && f.coplanar) return;
    const auto first_vote = static_cast<std::uint32_t>(i * kAlphaBins);
    const float alpha_in_bins =
        angle_about_x(to_x_axis_[i], points_[j] - points_[i]) * kAlphaBinsPerRad;
    const float bins[4] = {f.distance / step, f.a1 / kAngleStep, f.a2 / kAngleStep,
                           f.a3 / kAngleStep};
    for_each_spread_key(bins, distance_bins_, [&](std::uint32_t key) {
      keyed.push_back({key, first_vote, alpha_in_bins});
    });
  });
  // Counting sort into a dense table: the key space is small (distance bins x 15^3).
  offsets_.assign(
      static_cast<std::size_t>(distance_bins_) * kAngleBins * kAngleBins * kAngleBins + 1, 0);
  for (const Keyed& k : keyed) ++offsets_[k.key + 1];
  for (std::size_t k = 1; k < offsets_.size(); ++k) offsets_[k] += offsets_[k - 1];
  first_votes_.resize(keyed.size());
  alphas_in_bins_.resize(keyed.size());
  std::vector<std::uint32_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (const Keyed& k : keyed) {
    const std::uint32_t e = fill[k.key]++;
    first_votes_[e] = k.first_vote;
    alphas_in_bins_[e] = k.alpha_in_bins;
  }
  // One key past the key space, with no entries: the voting's key for a pair that casts no vote.
  offsets_.push_back(offsets_.back());
}

void PointPairModel::accumulate_votes(const PointCloud& scene,
                                      const std::vector<Neighbor>& neighbours, Index reference,
                                      const Eigen::Matrix3f& Rs,
                                      std::vector<std::uint32_t>& votes) const {
  const Eigen::Vector3f& sr = scene.points[reference];
  const Eigen::Vector3f& nr = scene.normals[reference];
  const PairQuantisation q{static_cast<float>(distance_step_), distance_bins_, skip_coplanar_,
                           static_cast<std::uint32_t>(offsets_.size() - 2)};
  constexpr std::uint32_t kBinsAtOnce = 256;
  std::uint32_t bins[kBinsAtOnce];
  NeighbourBlock block;
  for (std::size_t next = 0; next < neighbours.size();) {
    // A block of neighbours, then their features and keys in one vectorised pass.
    block.size = 0;
    for (; next < neighbours.size() && block.size < NeighbourBlock::kCapacity; ++next) {
      const Index i = neighbours[next].index;
      const Eigen::Vector3f& ni = scene.normals[i];
      if (i == reference || !ni.allFinite()) continue;
      const Eigen::Vector3f d = scene.points[i] - sr;
      const int b = block.size++;
      block.dx[b] = d.x(), block.dy[b] = d.y(), block.dz[b] = d.z();
      block.nx[b] = ni.x(), block.ny[b] = ni.y(), block.nz[b] = ni.z();
    }
    pair_feature_keys(q, nr, Rs, block);
    // Each pair votes for the (model point, alpha) bin of every model pair under its key.
    for (int b = 0; b < block.size; ++b) {
      const std::uint32_t k = block.key[b];
      const std::uint32_t end = offsets_[k + 1];
      for (std::uint32_t begin = offsets_[k]; begin < end; begin += kBinsAtOnce) {
        const std::uint32_t n = std::min(end - begin, kBinsAtOnce);
        vote_bins(block.alpha[b], &first_votes_[begin], &alphas_in_bins_[begin], n, bins);
        for (std::uint32_t e = 0; e < n; ++e) ++votes[bins[e]];
      }
    }
  }
}

namespace {

// The best `max_poses` bins of `votes` that `admissible` admits, as (votes, bin), strongest first;
// ties go to the lower index, so the result is deterministic. The scan goes a block of bins at a
// time: once the list is full, a block whose strongest bin does not beat the list's weakest holds
// no candidate (the blocks' maxima are one vectorised pass; most blocks are skipped). The
// admissibility is tested only for bins strong enough to enter the list, a handful per seed.
template <class Admissible>
std::vector<std::pair<std::uint32_t, std::uint32_t>> best_bins(
    const std::vector<std::uint32_t>& votes, int max_poses, const Admissible& admissible) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> best;
  best.reserve(static_cast<std::size_t>(max_poses) + 1);
  const auto consider = [&](std::uint32_t k) {
    if (votes[k] == 0) return;
    if (static_cast<int>(best.size()) < max_poses || votes[k] > best.back().first) {
      if (!admissible(k)) return;
      best.emplace_back(votes[k], k);
      std::stable_sort(best.begin(), best.end(),
                       [](const auto& a, const auto& b) { return a.first > b.first; });
      if (static_cast<int>(best.size()) > max_poses) best.pop_back();
    }
  };
  const auto bins = static_cast<std::uint32_t>(votes.size());
  for (std::uint32_t block = 0; block < bins; block += kScanBlock) {
    const std::uint32_t end = std::min(block + kScanBlock, bins);
    std::uint32_t strongest = 0;
    for (std::uint32_t k = block; k < end; ++k) strongest = std::max(strongest, votes[k]);
    if (strongest == 0) continue;
    if (static_cast<int>(best.size()) >= max_poses && strongest <= best.back().first) continue;
    for (std::uint32_t k = block; k < end; ++k) consider(k);
  }
  return best;
}

}  // namespace

void PointPairModel::vote(const PointCloud& scene, const RadiusGrid& grid, Index reference,
                          int max_poses, double min_fraction, std::vector<PoseVote>& out,
                          const TiltLimit* tilt) const {
  out.clear();
  const Eigen::Vector3f& sr = scene.points[reference];
  const Eigen::Vector3f& nr = scene.normals[reference];
  if (!sr.allFinite() || !nr.allFinite() || points_.empty()) return;
  const Eigen::Matrix3f Rs = rotation_to_x(nr);

  // Per-thread scratch: a search votes for a thousand seeds, and fresh buffers for each would cost
  // more in allocation than the voting itself.
  // Votes are counts: integers add without a floating-point latency in the loop's chain.
  thread_local std::vector<Neighbor> neighbours;
  thread_local std::vector<std::uint32_t> votes;
  grid.radius_unsorted(sr, static_cast<float>(diameter_), neighbours);
  votes.assign(points_.size() * kAlphaBins, 0);
  accumulate_votes(scene, neighbours, reference, Rs, votes);

  // x_scene = Ts^-1 Rx(alpha) Tm x_model, with Tm x = Rm (x - m), Ts x = Rs (x - s_r).
  const auto rotation = [&](std::uint32_t k) -> Eigen::Matrix3f {
    return Rs.transpose() * alpha_rotations()[k % kAlphaBins] * to_x_axis_[k / kAlphaBins];
  };
  const std::vector<std::pair<std::uint32_t, std::uint32_t>> best = best_bins(
      votes, max_poses, [&](std::uint32_t k) { return !tilt || tilt->admits(rotation(k)); });
  if (best.empty()) return;
  const float floor_votes =
      static_cast<float>(min_fraction) * static_cast<float>(best.front().first);
  for (const auto& [count, k] : best) {
    const auto v = static_cast<float>(count);
    if (v < floor_votes) break;
    const Eigen::Matrix3f R = rotation(k);
    PoseVote pv;
    pv.T_scene_model.linear() = R.cast<double>();
    pv.T_scene_model.translation() = (sr - R * points_[k / kAlphaBins]).cast<double>();
    pv.votes = v;
    out.push_back(pv);
  }
}

}  // namespace lmk::detail
