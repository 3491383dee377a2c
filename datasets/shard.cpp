// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/datasets/shard.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>

#include "lmk/geometry/error.h"
#include "lmk/geometry/hash.h"

namespace lmk {
namespace {

int shard_of(const Fnv1a& hash, int count) {
  return 1 + static_cast<int>(hash.value() % static_cast<std::uint64_t>(std::max(count, 1)));
}

}  // namespace

Shard parse_shard(const std::string& text) {
  Shard shard;
  char slash = 0, extra = 0;
  const int read =
      std::sscanf(text.c_str(), "%d%c%d%c", &shard.index, &slash, &shard.count, &extra);
  if (read != 3 || slash != '/' || shard.count < 1 || shard.index < 1 ||
      shard.index > shard.count) {
    throw Error("shard '" + text + "': must be K/N with 1 <= K <= N, such as 2/8");
  }
  return shard;
}

int pair_shard(const std::string& scene, const std::string& landmark, int count) {
  return shard_of(Fnv1a().add(scene).add(landmark), count);
}

int scene_shard(const std::string& scene, int count) { return shard_of(Fnv1a().add(scene), count); }

}  // namespace lmk
