// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/datasets/dataset.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/input_file.h"
#include "lmk/json/json_reader.h"

namespace lmk {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// One scene of dataset.json (its "scenes" array), `where` being its place there.
DatasetScene scene_from_json(const json& j, const std::string& where, const detail::JsonReader& r) {
  DatasetScene s;
  s.name = r.text(j, where, "name");
  s.file = r.text(j, where, "file");
  s.setting = r.text(j, where, "setting");
  s.T_scene_sensor = r.pose(r.field(j, where, "sensor_pose"), where + ".sensor_pose");
  if (j.contains("up") && !j["up"].is_null()) {
    const Eigen::Vector3d up = r.numbers(j["up"], where + ".up", 3);
    if (!(up.norm() > 0.0)) r.fail(where + ".up", "must not be zero");
    s.up = up.normalized();
  }
  const json& pairs = j.contains("pairs") ? j["pairs"] : json::array();
  if (!pairs.is_array()) r.fail(where + ".pairs", "must be an array");
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const std::string pw = detail::at(where, "pairs", k);
    DatasetPair p;
    p.landmark = r.text(pairs[k], pw, "landmark");
    const json& in_context = r.field(pairs[k], pw, "in_context");
    if (!in_context.is_boolean()) r.fail(pw + ".in_context", "must be true or false");
    p.in_context = in_context.get<bool>();
    const json& instances = r.field(pairs[k], pw, "instances");
    if (!instances.is_array()) r.fail(pw + ".instances", "must be an array of poses");
    for (std::size_t n = 0; n < instances.size(); ++n) {
      p.instances.push_back(r.pose(instances[n], detail::at(pw, "instances", n)));
    }
    if (pairs[k].contains("hidden")) {
      const json& hidden = pairs[k]["hidden"];
      if (!hidden.is_array() || hidden.size() != instances.size())
        r.fail(pw + ".hidden", "must be an array of one fraction per instance");
      for (std::size_t n = 0; n < hidden.size(); ++n) {
        if (!hidden[n].is_number() || !(hidden[n].get<double>() >= 0.0) ||
            !(hidden[n].get<double>() <= 1.0))
          r.fail(detail::at(pw, "hidden", n), "must be a fraction in [0, 1]");
        p.hidden.push_back(hidden[n].get<double>());
      }
    }
    if (pairs[k].contains("pose_check")) {
      const json& check = pairs[k]["pose_check"];
      const std::string cw = pw + ".pose_check";
      const auto disagreement = [&](const char* key) {
        const json& v = r.field(check, cw, key);
        if (!v.is_number() || !(v.get<double>() >= 0.0) || !std::isfinite(v.get<double>()))
          r.fail(cw + "." + key, "must be a finite number of at least 0");
        return v.get<double>();
      };
      p.pose_check = PoseCheck{disagreement("translation_m"), disagreement("rotation_rad")};
    }
    s.pairs.push_back(p);
  }
  return s;
}

Dataset parse(const json& j, const detail::JsonReader& r) {
  Dataset d;
  if (!j.is_object()) r.fail("", "must hold a JSON object");
  r.require_version(j, kDatasetFormatVersion, "dataset");
  d.name = r.text(j, "", "name");
  const json& landmarks = r.field(j, "", "landmarks");
  if (!landmarks.is_array()) r.fail("landmarks", "must be an array");
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    const std::string where = detail::at("", "landmarks", i);
    DatasetLandmark l{r.text(landmarks[i], where, "name"), r.text(landmarks[i], where, "file"), {}};
    if (landmarks[i].contains("symmetry_axis") && !landmarks[i]["symmetry_axis"].is_null()) {
      const Eigen::Vector3d axis =
          r.numbers(landmarks[i]["symmetry_axis"], where + ".symmetry_axis", 3);
      if (!(axis.norm() > 0.0)) r.fail(where + ".symmetry_axis", "must not be zero");
      l.symmetry.axis = axis.normalized();
      if (landmarks[i].contains("symmetry_order") && !landmarks[i]["symmetry_order"].is_null()) {
        const json& order = landmarks[i]["symmetry_order"];
        if (!order.is_number_integer() || order.get<int>() == 1 || order.get<int>() < 0) {
          r.fail(where + ".symmetry_order",
                 "must be 0 (an axis of revolution) or an integer n >= 2 (n-fold)");
        }
        l.symmetry.order = order.get<int>();
      }
    }
    d.landmarks.push_back(l);
  }
  const json& scenes = r.field(j, "", "scenes");
  if (!scenes.is_array()) r.fail("scenes", "must be an array");
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const std::string where = detail::at("", "scenes", i);
    d.scenes.push_back(scene_from_json(scenes[i], where, r));
  }
  return d;
}

// The file `name` of the dataset in `dir`: present, a regular file of at most kind's size, and
// inside `dir` after every symbolic link unless `files` says anywhere. Fails through `r`, at
// `where`, with one line.
void check_dataset_file(const std::string& dir, const std::string& name, const InputKind& kind,
                        DatasetFiles files, const std::string& where, const detail::JsonReader& r) {
  const fs::path path = fs::path(dir) / name;  // an absolute `name` replaces `dir`
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(path, ec)) || ec) {
    r.fail(where, "'" + printable(name) + "' does not exist in " + dir);
  }
  if (files == DatasetFiles::inside) {
    const bool inside = lies_within(path, dir, ec);
    if (ec) {
      r.fail(where,
             "'" + printable(name) + "' cannot be resolved (" + ec.message() +
                 (ec == std::errc::too_many_symbolic_link_levels ? ": a symbolic link loop" : "") +
                 ")");
    }
    if (!inside) {
      r.fail(where, "'" + printable(name) + "' lies outside the dataset directory " + dir +
                        " (lmk eval --allow-outside-files reads it anyway)");
    }
  }
  try {
    check_input_file(path.string(), kind);  // a FIFO or /dev/zero: a special file, not a scene
  } catch (const Error& e) {
    r.fail(where, e.what());
  }
}

// Names unique, pairs naming known landmarks once per scene, and every file present.
void check_consistency(const Dataset& d, const std::string& dir, DatasetFiles files,
                       const detail::JsonReader& r) {
  std::set<std::string> landmark_names, scene_names;
  for (std::size_t i = 0; i < d.landmarks.size(); ++i) {
    const std::string where = detail::at("", "landmarks", i);
    if (!landmark_names.insert(d.landmarks[i].name).second) {
      r.fail(where, "duplicate landmark name '" + d.landmarks[i].name + "'");
    }
    check_dataset_file(dir, d.landmarks[i].file, kLandmarkInput, files, where + ".file", r);
  }
  for (std::size_t i = 0; i < d.scenes.size(); ++i) {
    const DatasetScene& s = d.scenes[i];
    const std::string where = detail::at("", "scenes", i);
    if (!scene_names.insert(s.name).second) r.fail(where, "duplicate scene name '" + s.name + "'");
    check_dataset_file(dir, s.file, kCloudInput, files, where + ".file", r);
    std::set<std::string> paired;
    for (std::size_t k = 0; k < s.pairs.size(); ++k) {
      const std::string& name = s.pairs[k].landmark;
      if (!landmark_names.count(name))
        r.fail(detail::at(where, "pairs", k), "unknown landmark '" + name + "'");
      if (!paired.insert(name).second)
        r.fail(detail::at(where, "pairs", k), "landmark '" + name + "' paired twice");
      const std::vector<double>& hidden = s.pairs[k].hidden;
      if (!hidden.empty() && (hidden.size() != s.pairs[k].instances.size() ||
                              std::any_of(hidden.begin(), hidden.end(),
                                          [](double h) { return !(h >= 0.0 && h <= 1.0); })))
        r.fail(detail::at(where, "pairs", k) + ".hidden",
               "must hold one fraction in [0, 1] per instance");
    }
  }
}

}  // namespace

DatasetPair Dataset::pair(const DatasetScene& scene, const std::string& landmark) const {
  for (const DatasetPair& p : scene.pairs) {
    if (p.landmark == landmark) return p;
  }
  return {landmark, false, {}, {}, std::nullopt};
}

Dataset load_dataset(const std::string& dir, DatasetFiles files) {
  const std::string file = (fs::path(dir) / "dataset.json").string();
  const detail::JsonReader r(file);
  if (!fs::is_directory(dir)) r.fail("", "no such file (is '" + dir + "' a dataset directory?)");
  const std::string text = read_input_file(file, kDatasetInput);
  const Dataset d = parse(r.parse(text), r);
  check_consistency(d, dir, files, r);
  return d;
}

namespace {

json scene_to_json(const DatasetScene& s) {
  json pairs = json::array();
  for (const DatasetPair& p : s.pairs) {
    json instances = json::array();
    for (const auto& T : p.instances) instances.push_back(detail::pose_to_json(T));
    json pair = {{"landmark", p.landmark}, {"in_context", p.in_context}, {"instances", instances}};
    if (!p.hidden.empty()) pair["hidden"] = p.hidden;
    if (p.pose_check) {
      pair["pose_check"] = {{"translation_m", p.pose_check->translation},
                            {"rotation_rad", p.pose_check->rotation}};
    }
    pairs.push_back(pair);
  }
  return {{"name", s.name},
          {"file", s.file},
          {"setting", s.setting},
          {"sensor_pose", detail::pose_to_json(s.T_scene_sensor)},
          {"up", s.up ? detail::vector_to_json(*s.up) : json(nullptr)},
          {"pairs", pairs}};
}

}  // namespace

std::string scene_entry_text(const DatasetScene& scene) {
  return scene_to_json(scene).dump(2) + "\n";
}

DatasetScene parse_scene_entry(const std::string& text, const std::string& where) {
  const detail::JsonReader r(where);
  const json j = r.parse(text);
  if (!j.is_object()) r.fail("", "must hold a JSON object");
  return scene_from_json(j, "", r);
}

std::string views_landmark_name(const std::string& name, std::size_t views) {
  return views == 1 ? name : name + "-v" + std::to_string(views);
}

void save_dataset(const std::string& dir, const Dataset& d) {
  const std::string file = (fs::path(dir) / "dataset.json").string();
  json landmarks = json::array(), scenes = json::array();
  for (const DatasetLandmark& l : d.landmarks) {
    json entry = {{"name", l.name}, {"file", l.file}, {"symmetry_axis", nullptr}};
    if (l.symmetry.axis) {
      const Eigen::Vector3d& a = *l.symmetry.axis;
      entry["symmetry_axis"] = detail::vector_to_json(a);
      entry["symmetry_order"] = l.symmetry.order;
    }
    landmarks.push_back(entry);
  }
  for (const DatasetScene& s : d.scenes) scenes.push_back(scene_to_json(s));
  const json j = {{"format", "lmk-dataset"},
                  {"version", kDatasetFormatVersion},
                  {"name", d.name},
                  {"landmarks", landmarks},
                  {"scenes", scenes}};
  // Validate what is about to be written exactly as a reader would, before writing it.
  const detail::JsonReader r(file);
  check_consistency(parse(j, r), dir, DatasetFiles::inside, r);
  write_file_atomically(file, [&](const fs::path& tmp) {
    std::ofstream out(tmp);
    out << j.dump(2) << "\n";
    if (!out) throw Error(file + ": write failed");
  });
}

}  // namespace lmk
