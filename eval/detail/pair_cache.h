// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The evaluation's cache of pair results: one JSON file per (scene, landmark) pair under
// CACHE/evaluations/KEY/, written as soon as the pair is searched, so that an interrupted
// evaluation resumes from what it finished (eval/evaluation.h).

#include <filesystem>
#include <optional>
#include <string>

#include "lmk/eval/evaluation.h"

namespace lmk::detail {

class PairCache {
 public:
  /// The cache of search configuration `key` (evaluation_cache_key) under `cache_dir`, which is
  /// created; an empty `cache_dir` is no cache: nothing is read or written.
  PairCache(const std::string& cache_dir, const std::string& key);

  /// The stored result of (scene, landmark), or nothing: not stored, damaged, or another pair's.
  std::optional<PairResult> read(const std::string& scene, const std::string& landmark) const;

  /// Stores `searched` as its pair's file, atomically (nothing without a cache), and returns it as
  /// the file holds it, whether or not there is one: a box pose goes through its quaternion there,
  /// which is not bit-exact, so a fresh result and a resumed one take the same way and agree.
  /// `threshold` and `tolerance` mark each match correct or not in the file
  /// (pair_result_to_json).
  PairResult store(const PairResult& searched, double threshold,
                   const MatchTolerance& tolerance) const;

  /// The file of the pair (scene, landmark): named by a hash of the names, since scene names are
  /// free text; the file repeats them.
  std::filesystem::path file(const std::string& scene, const std::string& landmark) const;

 private:
  std::filesystem::path dir_;
};

}  // namespace lmk::detail
