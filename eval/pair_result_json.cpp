// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/internal/pair_result_json.h"

#include "lmk/geometry/error.h"
#include "lmk/json/box_json.h"
#include "lmk/json/pose_json.h"
#include "lmk/search/internal/confidence_json.h"
#include "lmk/search/internal/terms_json.h"

namespace lmk::detail {

using nlohmann::json;

namespace {

template <typename T>
T get(const json& j, const char* key, const std::string& where) {
  try {
    return json_field(j, key, where).get<T>();
  } catch (const json::exception&) {
    throw Error(where + "." + key + ": has the wrong type");
  }
}

}  // namespace

json pair_result_to_json(const PairResult& p, double threshold, const MatchTolerance& tolerance) {
  json truth = json::array(), found = json::array();
  for (const auto& T : p.truth) truth.push_back(pose_to_json(T));
  // Each match says whether it is correct at the evaluation's threshold (assumption 1's rule),
  // so the report's per-scene table needs no protocol code of its own.
  // Matches come best first, so those within the threshold are the first assigned.size().
  const auto assigned = assign_matches(matches_within(p, threshold), tolerance);
  for (std::size_t i = 0; i < p.found.size(); ++i) {
    const FoundBox& f = p.found[i];
    json m = box_to_json(f.box);
    m["error"] = f.error;
    m["within_threshold"] = f.error < threshold;
    m["correct"] = i < assigned.size() && assigned[i].has_value();
    m["terms"] = terms_to_json(f.terms);
    m["confidence"] = confidence_to_json(f.confidence);
    found.push_back(m);
  }
  return {{"scene", p.scene},
          {"landmark", p.landmark},
          {"setting", p.setting},
          {"in_context", p.in_context},
          {"symmetry_axis", p.symmetry.axis ? vector_to_json(*p.symmetry.axis) : json(nullptr)},
          {"symmetry_order", p.symmetry.order},
          {"symmetry_centre", vector_to_json(p.symmetry.centre)},
          {"symmetry_from_capture", p.symmetry_from_capture},
          {"truth", truth},
          {"found", found},
          {"seconds", p.seconds},
          {"seeds", p.seeds},
          {"rejections", p.rejections},
          {"sensor_position", vector_to_json(p.sensor_position)},
          {"truth_hidden", p.truth_hidden}};
}

PairResult pair_result_from_json(const json& j, const std::string& where) {
  PairResult p;
  p.scene = get<std::string>(j, "scene", where);
  p.landmark = get<std::string>(j, "landmark", where);
  p.setting = get<std::string>(j, "setting", where);
  p.in_context = get<bool>(j, "in_context", where);
  const json& axis = json_field(j, "symmetry_axis", where);
  if (!axis.is_null()) p.symmetry.axis = numbers_from_json(axis, 3, where + ".symmetry_axis");
  p.symmetry.order = get<int>(j, "symmetry_order", where);
  // Since issue #59; a pair cached before has its symmetry about the box centre, from the dataset.
  if (j.contains("symmetry_centre"))
    p.symmetry.centre = numbers_from_json(j["symmetry_centre"], 3, where + ".symmetry_centre");
  if (j.contains("symmetry_from_capture"))
    p.symmetry_from_capture = get<bool>(j, "symmetry_from_capture", where);
  for (const json& t : json_field(j, "truth", where)) p.truth.push_back(pose_from_json(t, where));
  for (const json& m : json_field(j, "found", where)) {
    p.found.push_back(
        {box_from_json(m, where + ".found"), get<double>(m, "error", where),
         terms_from_json(json_field(m, "terms", where), where + ".terms"),
         confidence_from_json(json_field(m, "confidence", where), where + ".confidence")});
  }
  p.seconds = get<double>(j, "seconds", where);
  p.seeds = get<std::size_t>(j, "seeds", where);
  p.rejections = get<std::string>(j, "rejections", where);
  for (const json& h : json_field(j, "truth_hidden", where)) {
    if (!h.is_number()) throw Error(where + ".truth_hidden: must hold numbers");
    p.truth_hidden.push_back(h.get<double>());
  }
  p.sensor_position =
      numbers_from_json(json_field(j, "sensor_position", where), 3, where + ".sensor_position");
  return p;
}

}  // namespace lmk::detail
