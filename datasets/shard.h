// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One machine's share of a cluster job (docs/cluster.md): the scenes a generation shard renders,
// the pairs an evaluation shard searches. Membership is a hash of names, never a position, so that
// a dataset that grows moves nothing already assigned to another shard.

#include <string>

namespace lmk {

/// Shard `index` of `count`, 1-based.
struct Shard {
  int index = 1;
  int count = 1;
};

/// "K/N" as a Shard; lmk::Error unless 1 <= K <= N.
Shard parse_shard(const std::string& text);

/// The shard (1 to `count`) of the pair (scene, landmark).
int pair_shard(const std::string& scene, const std::string& landmark, int count);

/// The shard (1 to `count`) of the scene called `scene`.
int scene_shard(const std::string& scene, int count);

}  // namespace lmk
