// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A small seeded generator whose sequence is fixed by its definition, not by the standard
// library: std::uniform_int_distribution differs between implementations, and lmk promises the
// same samples for the same seed everywhere.

#include <cstdint>

namespace lmk {

/// SplitMix64's output function: a bijective 64-bit mix whose outputs look independent for
/// neighbouring inputs. Also a stateless hash of a value (spread seeds draw one per cell with it).
inline std::uint64_t splitmix64_mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// SplitMix64 (Steele, Lea & Flood 2014): 64-bit state, passes BigCrush, trivially seedable.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next() { return splitmix64_mix(state_ += 0x9e3779b97f4a7c15ULL); }

  /// Uniform in [0, n) for n > 0, without modulo bias (Lemire's multiply-and-reject).
  std::uint64_t uniform_index(std::uint64_t n) {
    unsigned __int128 m = static_cast<unsigned __int128>(next()) * n;
    auto low = static_cast<std::uint64_t>(m);
    if (low < n) {
      const std::uint64_t threshold = (0 - n) % n;
      while (low < threshold) {
        m = static_cast<unsigned __int128>(next()) * n;
        low = static_cast<std::uint64_t>(m);
      }
    }
    return static_cast<std::uint64_t>(m >> 64);
  }

  /// Uniform in [0, 1) with 53 random bits.
  double uniform01() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

  /// Standard normal by Box-Muller (uses two uniforms per call; simple and deterministic).
  double normal();

 private:
  std::uint64_t state_;
};

}  // namespace lmk
