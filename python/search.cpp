// SPDX-License-Identifier: BSD-3-Clause
// lmk.find: a search with its settings as keywords, named, converted and checked by the settings'
// own descriptions (search/find_settings.h) as `lmk find`'s flags are; the GIL released while it
// runs (docs/python.md, "Search").
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <thread>

#include "bindings.h"
#include "lmk/geometry/error.h"
#include "lmk/search/confidence/confidence_calibration.h"
#include "lmk/search/find_landmark.h"
#include "lmk/search/internal/error_metric_json.h"
#include "lmk/search/internal/find_result_json.h"
#include "lmk/search/metrics/error_metrics.h"

namespace lmk::python {

std::string setting_text(const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::sequence>(value) || py::isinstance<py::array>(value)) {
    std::string text;
    for (const py::handle& v : value) text += (text.empty() ? "" : " ") + setting_text(v);
    return text;
  }
  return py::str(value).cast<std::string>();
}

std::string setting_key(std::string name) {
  std::replace(name.begin(), name.end(), '_', '-');
  return name;
}

void set_from_keywords(const py::kwargs& keywords,
                       const std::function<void(const std::string& name, const std::string& key,
                                                const std::string& text)>& set) {
  for (const auto& [name, value] : keywords) {
    const std::string python_name = name.cast<std::string>();
    try {
      set(python_name, setting_key(python_name), setting_text(value));
    } catch (const Error& e) {
      throw py::value_error(e.what());
    }
  }
}

FindSettings settings_from_keywords(const py::kwargs& keywords) {
  FindSettings settings;
  set_from_keywords(
      keywords, [&settings](const std::string&, const std::string& key, const std::string& text) {
        set_find_setting(settings, key, text);
      });
  try {
    validate(settings);
  } catch (const Error& e) {
    throw py::value_error(e.what());
  }
  return settings;
}

namespace {

// The matches of `lmk find --json`, each with its pose (the capture frame in the scene frame) and
// its box as arrays too.
py::list matches_to_python(const std::vector<Match>& matches, const nlohmann::json& j) {
  py::list out;
  for (std::size_t i = 0; i < matches.size(); ++i) {
    py::dict d = json_to_python(j[i]);
    d["pose"] = pose_to_array(matches[i].T_scene_capture);
    d["box"] = box_to_dict(matches[i].box);
    out.append(d);
  }
  return out;
}

}  // namespace

namespace {

// lmk.find: the search with the GIL released, heard from through `progress` and Python's signal
// handlers, its result as `lmk find --json` writes it.
py::dict find_from_python(const PointCloud& scene, const Landmark& landmark, bool rejected,
                          const std::function<void(std::size_t, std::size_t)>& progress,
                          const std::string& calibration, const py::kwargs& kwargs) {
  FindSettings settings = settings_from_keywords(kwargs);
  if (!calibration.empty()) {  // a file of lmk calibrate-confidence, as `lmk find --calibration`
    settings.selection.calibration =
        std::make_shared<const ConfidenceCalibration>(read_confidence_calibration(calibration));
  }
  // After each seed, from the search's threads: Python's signal handlers run (Ctrl-C ends
  // the search there), then `progress`. Each report takes the GIL; the search itself runs
  // without it. Without `progress`, only the reports on the calling thread take it, and
  // only when that is Python's main thread, the one thread that runs signal handlers: two
  // searches from two other threads then never queue for the GIL. The threads count seeds
  // before they queue for the GIL, so their counts can arrive out of order: Python hears a
  // count kept under the GIL instead, which rises by one each time.
  const std::thread::id caller = std::this_thread::get_id();
  const bool caller_handles_signals =
      PyThread_get_thread_ident() ==
      py::module_::import("threading").attr("main_thread")().attr("ident").cast<unsigned long>();
  std::size_t heard = 0;
  settings.execution.progress = [&](std::size_t, std::size_t total) {
    if (!progress && !(caller_handles_signals && std::this_thread::get_id() == caller)) {
      return;
    }
    const py::gil_scoped_acquire acquire;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    ++heard;
    if (progress) progress(heard, total);
  };
  FindResult result;
  {
    const py::gil_scoped_release release;
    result = find_landmark(scene, landmark, settings);
  }
  const nlohmann::json j = detail::find_result_to_json(result, rejected);
  py::dict out;
  out["matches"] = matches_to_python(result.matches, j["matches"]);
  out["stats"] = json_to_python(j["stats"]);
  out["error_unit"] = j.value("error_unit", "");
  if (rejected) {
    std::vector<Match> candidates;
    for (const Rejection& r : result.rejected) candidates.push_back(r.candidate);
    out["rejected"] = matches_to_python(candidates, j["rejected"]);
  }
  return out;
}

// lmk.error_metrics(): the registry, with what each metric says of itself.
py::list error_metrics_to_python() {
  py::list out;
  for (const ErrorMetric& metric : error_metrics()) {
    out.append(json_to_python(detail::error_metric_to_json(metric)));
  }
  return out;
}

}  // namespace

void bind_search(py::module_& m) {
  m.def(
      "find", &find_from_python, py::arg("scene"), py::arg("landmark"), py::kw_only(),
      py::arg("rejected") = false, py::arg("progress") = nullptr, py::arg("calibration") = "",
      "Finds every instance of `landmark` in `scene`. Settings are keywords named as `lmk find`'s "
      "flags (max_tilt=30 for --max-tilt 30), in their units and checked by their rules "
      "(ValueError otherwise). Returns {'matches': [...], 'stats': {...}} as `lmk find --json` "
      "writes them (and 'error_unit', the metric's: 'm' or 'sd'), each match with its 'pose' (4x4, "
      "the capture frame in the scene frame) and "
      "'box'; with rejected=True also the rejected candidates and their 'reason'. "
      "progress(done, total) hears of each seed. calibration: a confidence calibration file of "
      "`lmk calibrate-confidence` (default: lmk's built-in one). Ctrl-C (KeyboardInterrupt) ends "
      "the search at "
      "its next seed.");
  m.def(
      "find_setting_keys",
      [] {
        std::vector<std::string> keys;
        for (std::string k : find_setting_keys()) {
          std::replace(k.begin(), k.end(), '-', '_');
          keys.push_back(k);
        }
        return keys;
      },
      "The keywords lmk.find takes: every search setting, as `lmk find`'s flags name them.");
  m.def("error_metrics", &error_metrics_to_python,
        "Every error metric lmk.find's `metric` keyword takes, built in or from a plugin that "
        "$LMK_METRIC_PLUGINS names: its name, description, default threshold and 'error_unit' ('m' "
        "or 'sd'), how errors are shown ('shown_unit', 'shown_scale'), whether the fast search has "
        "a coarse score of it and the bound it prunes at (None without one), and whether its "
        "residuals are in units of the depth noise, it needs the empty-space distances and it "
        "hides occluded points: as `lmk metrics --json` writes them.");
}

}  // namespace lmk::python
