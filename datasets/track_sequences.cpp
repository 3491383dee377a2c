// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/datasets/track_sequences.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/input_file.h"
#include "lmk/json/json_reader.h"

namespace lmk {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string sequences_file(const std::string& dir) {
  return (fs::path(dir) / "sequences.json").string();
}

// The checks load and save share: names known to the dataset, a carry inside its sequence.
void check_sequences(const Dataset& dataset, const std::vector<TrackSequence>& sequences,
                     const detail::JsonReader& r) {
  std::set<std::string> scenes, landmarks, names;
  for (const DatasetScene& s : dataset.scenes) scenes.insert(s.name);
  for (const DatasetLandmark& l : dataset.landmarks) landmarks.insert(l.name);
  for (std::size_t i = 0; i < sequences.size(); ++i) {
    const TrackSequence& s = sequences[i];
    const std::string where = detail::at("", "sequences", i);
    if (!names.insert(s.name).second) r.fail(where, "a second sequence named '" + s.name + "'");
    if (!landmarks.count(s.landmark))
      r.fail(where, "unknown landmark '" + s.landmark + "' (not in dataset.json)");
    if (s.frames.empty()) r.fail(where, "'frames' lists no frame");
    for (std::size_t f = 0; f < s.frames.size(); ++f) {
      if (!scenes.count(s.frames[f]))
        r.fail(detail::at(where, "frames", f),
               "unknown scene '" + s.frames[f] + "' (not in dataset.json)");
    }
    if (s.carry && !(s.carry->from < s.carry->back && s.carry->back < s.frames.size()))
      r.fail(where + ".carry", "needs from < back < the number of frames");
  }
}

std::size_t frame_index(const detail::JsonReader& r, const json& j, const std::string& where,
                        const std::string& key) {
  const json& v = r.field(j, where, key);
  if (!v.is_number_unsigned()) r.fail(where, "'" + key + "' must be a frame index (0, 1, ...)");
  return v.get<std::size_t>();
}

// A disagreement: a finite number, 0 or more.
double distance(const detail::JsonReader& r, const json& j, const std::string& where,
                const std::string& key) {
  const json& v = r.field(j, where, key);
  if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0.0)
    r.fail(where, "'" + key + "' must be a finite number, 0 or more");
  return v.get<double>();
}

TrackSequence parse_sequence(const detail::JsonReader& r, const json& j, const std::string& where) {
  if (!j.is_object()) r.fail(where, "must be an object");
  TrackSequence s;
  s.name = r.text(j, where, "name");
  s.landmark = r.text(j, where, "landmark");
  const json& frames = r.field(j, where, "frames");
  if (!frames.is_array()) r.fail(where, "'frames' must be an array of scene names");
  if (frames.size() > kMaxTrackFrames) {
    r.fail(where, "'frames' lists " + std::to_string(frames.size()) + " frames; at most " +
                      std::to_string(kMaxTrackFrames));
  }
  for (std::size_t f = 0; f < frames.size(); ++f) {
    if (!frames[f].is_string()) r.fail(detail::at(where, "frames", f), "must be a scene name");
    s.frames.push_back(frames[f].get<std::string>());
  }
  if (j.contains("carry") && !j["carry"].is_null()) {
    const std::string in = where + ".carry";
    s.carry = Carry{frame_index(r, j["carry"], in, "from"), frame_index(r, j["carry"], in, "back")};
  }
  if (j.contains("pose_check") && !j["pose_check"].is_null()) {
    const std::string in = where + ".pose_check";
    s.pose_check = PoseCheck{distance(r, j["pose_check"], in, "translation_m"),
                             distance(r, j["pose_check"], in, "rotation_rad")};
  }
  return s;
}

}  // namespace

bool has_track_sequences(const std::string& dir) { return fs::exists(sequences_file(dir)); }

std::vector<TrackSequence> load_track_sequences(const std::string& dir, const Dataset& dataset) {
  const std::string file = sequences_file(dir);
  const detail::JsonReader r(file);
  if (!fs::exists(file))
    r.fail("", "no such file: '" + dir + "' holds no sequences (lmk gen --preset moving)");
  const json j = r.parse(read_input_file(file, kDatasetInput));
  if (!j.is_object()) r.fail("", "must be a JSON object");
  r.require_version(j, kSequencesFormatVersion, "sequences");
  const json& list = r.field(j, "", "sequences");
  if (!list.is_array()) r.fail("sequences", "must be an array");
  if (list.size() > kMaxTrackSequences) {
    r.fail("sequences", "lists " + std::to_string(list.size()) + " sequences; at most " +
                            std::to_string(kMaxTrackSequences));
  }
  std::vector<TrackSequence> sequences;
  for (std::size_t i = 0; i < list.size(); ++i)
    sequences.push_back(parse_sequence(r, list[i], detail::at("", "sequences", i)));
  check_sequences(dataset, sequences, r);
  return sequences;
}

void save_track_sequences(const std::string& dir, const Dataset& dataset,
                          const std::vector<TrackSequence>& sequences) {
  check_sequences(dataset, sequences, detail::JsonReader(sequences_file(dir)));
  json list = json::array();
  for (const TrackSequence& s : sequences) {
    json j = {{"name", s.name}, {"landmark", s.landmark}, {"frames", s.frames}};
    if (s.carry) j["carry"] = {{"from", s.carry->from}, {"back", s.carry->back}};
    if (s.pose_check) {
      j["pose_check"] = {{"translation_m", s.pose_check->translation},
                         {"rotation_rad", s.pose_check->rotation}};
    }
    list.push_back(j);
  }
  write_text_atomically(
      sequences_file(dir),
      json({{"version", kSequencesFormatVersion}, {"sequences", list}}).dump(1) + "\n");
}

}  // namespace lmk
