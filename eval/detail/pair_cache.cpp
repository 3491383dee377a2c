// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/detail/pair_cache.h"

#include "lmk/eval/internal/pair_result_json.h"
#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/hash.h"
#include "lmk/geometry/input_file.h"

namespace lmk::detail {

namespace fs = std::filesystem;

PairCache::PairCache(const std::string& cache_dir, const std::string& key)
    : dir_(cache_dir.empty() ? fs::path() : fs::path(cache_dir) / "evaluations" / key) {
  if (dir_.empty()) return;
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw Error(dir_.string() + ": cannot create the cache directory (" + ec.message() + ")");
}

std::optional<PairResult> PairCache::read(const std::string& scene,
                                          const std::string& landmark) const {
  if (dir_.empty()) return std::nullopt;
  try {
    const std::string path = file(scene, landmark).string();
    std::error_code ec;
    if (!fs::exists(path, ec)) return std::nullopt;
    const nlohmann::json j = nlohmann::json::parse(read_input_file(path, kJsonInput));
    PairResult r = pair_result_from_json(j, path);
    if (r.scene != scene || r.landmark != landmark) return std::nullopt;  // a hash collision
    r.from_cache = true;
    return r;
  } catch (const std::exception&) {
    return std::nullopt;  // a damaged entry (an interrupted write cannot leave one) is re-run
  }
}

PairResult PairCache::store(const PairResult& searched, double threshold,
                            const MatchTolerance& tolerance) const {
  const nlohmann::json entry = pair_result_to_json(searched, threshold, tolerance);
  if (!dir_.empty())
    write_text_atomically(file(searched.scene, searched.landmark), entry.dump() + "\n");
  return pair_result_from_json(entry, searched.scene);
}

fs::path PairCache::file(const std::string& scene, const std::string& landmark) const {
  return dir_ / (Fnv1a().add(scene).add(landmark).hex() + ".json");
}

}  // namespace lmk::detail
