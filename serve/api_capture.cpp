// SPDX-License-Identifier: BSD-3-Clause
// Capture endpoints: the box guess from a clicked point, the distinctiveness check, and writing
// the landmark into the library (docs/landmarks.md; the paper's capture step).
#include "lmk/geometry/error.h"
#include "lmk/json/box_json.h"
#include "lmk/json/pose_json.h"
#include "lmk/landmark/box_guess.h"
#include "lmk/landmark/capture_views.h"
#include "lmk/landmark/internal/capture_findings_json.h"
#include "lmk/landmark/slide_check.h"
#include "lmk/search/capture_check.h"
#include "lmk/search/internal/find_result_json.h"
#include "lmk/serve/api.h"
#include "lmk/serve/api_error.h"
#include "lmk/serve/request_fields.h"

namespace lmk::serve {
namespace {

// The scenes a capture cuts its landmark from: the request's "scene", then its "views" (issue #35,
// "add a view"), each by id. Read before any work, so that an unknown id is a 404 at once.
std::vector<Scene> capture_scenes(const SceneStore& scenes, const nlohmann::json& body,
                                  const std::string& what) {
  std::vector<Scene> out{scenes.get(required_string(body, "scene", what))};
  for (const std::string& id : optional_names(body, "views", {}, what, kMaxLandmarkViews))
    out.push_back(scenes.get(id));
  if (out.size() > kMaxLandmarkViews) {
    throw bad_request(what + ": views: a landmark takes at most " +
                      std::to_string(kMaxLandmarkViews) + " scenes");
  }
  return out;
}

// The landmark cut out of the request's scenes with the request's box: one scene as `lmk capture
// SCENE`, several as `lmk capture A B ...` (place_views, then capture_views): "poses" (one per
// scene) places them, "register" refines that, and without poses each further view is registered
// onto the first. Each registration is added to `registrations`.
Landmark capture_from(const std::vector<Scene>& scenes, const nlohmann::json& body,
                      const FindSettings& find, const std::string& name, const std::string& what,
                      nlohmann::json& registrations) {
  const Box box = required_box(body, "box", what);
  CaptureSettings settings;
  prepare_capture_as_search(find.scene, settings);
  settings.allow_flat = optional_bool(body, "allow_flat", false, what);
  ViewPlacement placement;
  placement.poses = optional_poses(body, "poses", what);
  placement.register_views = optional_bool(body, "register", false, what);
  std::vector<const PointCloud*> clouds;
  for (const Scene& scene : scenes) clouds.push_back(scene.cloud.get());
  // lmk::Error: 422, with the reason (a registration refused says its overlap and residual).
  const std::vector<CaptureView> views =
      place_views(clouds, box, placement, [&](std::size_t view, const ViewRegistration& r) {
        registrations.push_back({{"view", view},
                                 {"overlap", r.overlap},
                                 {"residual", r.residual},
                                 {"moved", r.moved},
                                 {"turned", r.turned}});
      });
  return capture_views(views, box, name, settings);
}

// The verdict the page shows before the file is written: the capture check (landmark/
// capture_check.h), whose findings it stores in `landmark`. The look-alike search reports each seed
// to `progress`, where a cancelled or abandoned job ends. With the landmark's views and how each
// further one was registered (`registrations`).
nlohmann::json verdict(Landmark& landmark, const PointCloud& scene,
                       const nlohmann::json& registrations, JobProgress& progress) {
  FindSettings find;
  find.scene.up = landmark.up;  // the capture frame is the scene frame
  find.execution.stop = progress.stop_check();
  const std::string what = "searching '" + landmark.name + "' in its own scene";
  find.execution.progress = [&progress, &what](std::size_t done, std::size_t total) {
    progress.report(0.2 + 0.8 * static_cast<double>(done) / static_cast<double>(total), what);
  };
  const CaptureCheck check = check_capture(landmark, &scene, find);
  landmark.findings = check.findings;
  const nlohmann::json findings = detail::capture_findings_to_json(check.findings);
  if (!check.look_alikes) {  // a flat landmark
    return {{"distinctive", true},
            {"checked", false},
            {"findings", findings},
            {"views", landmark.view_count()},
            {"registrations", registrations},
            {"message", "a flat patch matches wherever it fits: no distinctiveness check"}};
  }
  const DistinctivenessReport& report = *check.look_alikes;
  nlohmann::json others = nlohmann::json::array();
  for (const Match& m : report.other_instances) {
    nlohmann::json o = detail::match_to_json(m);
    o["box"] = detail::box_to_json(m.box);
    others.push_back(o);
  }
  const bool distinctive = report.found_itself && report.other_instances.empty();
  std::string message;
  if (!report.found_itself) {
    message = "the search does not find '" + landmark.name +
              "' in its own scene: too few points or too little shape to be found reliably";
  } else if (!distinctive) {
    message = "'" + landmark.name + "' also matches " +
              std::to_string(report.other_instances.size()) +
              " other place(s) in its own scene: a robot could take them for it; draw the box "
              "with more context or more empty margin";
  } else {
    message = "'" + landmark.name + "' is distinctive in its scene";
  }
  // The slide check (landmark/slide_check.h), apart from the look-alikes: advice, not a refusal.
  const std::vector<std::string> slides = describe_slides(check.slides, landmark.box);
  for (const std::string& line : slides) message += "; " + line;
  return {{"distinctive", distinctive},
          {"slides", slides},
          {"checked", true},
          {"findings", findings},
          {"found_itself", report.found_itself},
          {"other_instances", others},
          {"metric", report.search.stats.metric},
          {"seconds", report.search.stats.seconds_total},
          {"views", landmark.view_count()},
          {"registrations", registrations},
          {"message", message}};
}

nlohmann::json landmark_summary(const std::string& name, const Landmark& l) {
  return {{"name", name},
          {"points", l.points.size()},
          {"box", detail::box_to_json(l.box)},
          {"up", detail::vector_to_json(l.up)},
          {"allow_flat", l.settings.allow_flat},
          {"views", l.view_count()},
          {"colour", l.points.has_colors()},
          {"warnings", l.findings.warnings()}};
}

// Writes `landmark` into `library` under `name`; the answer of a capture: its summary and file.
nlohmann::json save_and_summarise(LandmarkLibrary& library, const std::string& name,
                                  const Landmark& landmark, bool overwrite) {
  const std::filesystem::path file = library.save(landmark, overwrite);
  nlohmann::json j = landmark_summary(name, landmark);
  j["file"] = file.filename().string();
  return j;
}

}  // namespace

ApiResponse Api::guess(const std::string& body_text) const {
  const nlohmann::json body = parse_body(body_text, "guess");
  const Scene scene = scenes_.get(required_string(body, "scene", "guess"));
  BoxGuessSettings settings;
  settings.margin = optional_number(body, "margin", settings.margin, "guess");
  try {
    validate(settings);
  } catch (const Error& e) {
    throw bad_request("guess: " + std::string(e.what()));
  }
  const BoxGuess g = guess_box(*scene.cloud, required_point(body, "point", "guess"), settings);
  nlohmann::json j = {{"box", detail::box_to_json(g.box)},
                      {"object_box", detail::box_to_json(g.object_box)},
                      {"object_points", g.object.size()}};
  j["support"] =
      g.support ? nlohmann::json{g.support->x(), g.support->y(), g.support->z(), g.support->w()}
                : nlohmann::json(nullptr);
  return {200, j};
}

ApiResponse Api::check(const std::string& body_text) {
  const nlohmann::json body = parse_body(body_text, "check");
  const std::vector<Scene> scenes = capture_scenes(scenes_, body, "check");
  const std::string name = body.contains("name") ? required_string(body, "name", "check") : "new";
  // The box and poses are read now, so that a bad one is a 400 here rather than a failed job.
  required_box(body, "box", "check");
  optional_poses(body, "poses", "check");
  const FindSettings find = scene_find_settings();
  MemoryBudget::Reservation memory = reserve_search(scenes.front(), find.scene, "check");
  return run_job(
      "check", body, std::move(memory), [scenes, body, find, name](JobProgress& progress) {
        progress.report(0.0, "capturing '" + name + "'");
        nlohmann::json registrations = nlohmann::json::array();
        Landmark landmark = capture_from(scenes, body, find, name, "check", registrations);
        progress.report(0.2, "searching '" + name + "' in its own scene");
        return verdict(landmark, *scenes.front().cloud, registrations, progress);
      });
}

ApiResponse Api::landmarks() const {
  nlohmann::json list = nlohmann::json::array();
  for (const std::string& name : library_.names()) {
    try {
      list.push_back(landmark_summary(name, *library_.load(name)));
    } catch (const Error& e) {
      list.push_back({{"name", name}, {"error", e.what()}});  // listed, so the user sees why
    }
  }
  return {200, {{"landmarks", list}, {"directory", library_.directory().string()}}};
}

ApiResponse Api::landmark(const std::string& name) const {
  checked_name(name, "landmark");
  if (!library_.contains(name))
    throw not_found("no landmark '" + printable(name, kEchoedBytes) + "'");
  const auto l = library_.load(name);
  nlohmann::json j = landmark_summary(name, *l);
  nlohmann::json points = nlohmann::json::array();
  for (const Eigen::Vector3f& p : l->points.points)
    points.push_back(detail::vector_to_json(p.cast<double>()));
  j["positions"] = points;
  return {200, j};
}

ApiResponse Api::save_landmark(const std::string& body_text) {
  const nlohmann::json body = parse_body(body_text, "capture");
  const std::vector<Scene> scenes = capture_scenes(scenes_, body, "capture");
  const Scene& scene = scenes.front();
  const std::string name = checked_name(required_string(body, "name", "capture"), "capture");
  const bool overwrite = optional_bool(body, "overwrite", false, "capture");
  const bool check_first = optional_bool(body, "check", false, "capture");
  required_box(body, "box", "capture");  // a bad request is told so before anything else
  optional_poses(body, "poses", "capture");
  if (!overwrite && library_.contains(name)) {
    throw conflict("capture: a landmark '" + name +
                   "' exists already; choose another name or set overwrite");
  }
  nlohmann::json registrations = nlohmann::json::array();
  Landmark landmark =
      capture_from(scenes, body, scene_find_settings(), name, "capture", registrations);
  if (!check_first) {
    // What the capture check measures without a search (the noise, the slides) still travels with
    // the landmark; the look-alike check is the request's "check".
    landmark.findings = check_capture(landmark, scene.cloud.get(), {}, false).findings;
    nlohmann::json j = save_and_summarise(library_, name, landmark, overwrite);
    j["registrations"] = registrations;
    return {201, j};
  }
  // The check is a search: it runs on the worker pool like any other, and the landmark is written
  // by the job once it passes. The request waits for it as a "wait": true POST does, at most
  // kMaxRequestWait; a longer check answers 202 with the job to poll.
  nlohmann::json job_body = body;
  job_body["wait"] = true;
  const auto shared = std::make_shared<const Landmark>(landmark);
  LandmarkLibrary& library = library_;
  ApiResponse answer = run_job(
      "capture", job_body, reserve_search(scene, scene_find_settings().scene, "capture"),
      [shared, scene, overwrite, name, registrations, &library](JobProgress& progress) {
        Landmark checked_landmark = *shared;
        const nlohmann::json checked =
            verdict(checked_landmark, *scene.cloud, registrations, progress);
        if (!checked["distinctive"].get<bool>()) {
          throw ApiError(409, "capture: not written: " + checked["message"].get<std::string>(),
                         {{"verdict", checked}});
        }
        nlohmann::json j = save_and_summarise(library, name, checked_landmark, overwrite);
        j["verdict"] = checked;
        j["registrations"] = registrations;
        return j;
      });
  // A finished capture answers as one without a check: the landmark, 201; or the refusal.
  if (answer.status == 200) return {201, answer.body["result"]};
  if (answer.status != 202) {
    nlohmann::json refusal = {{"error", answer.body["error"]}};
    if (answer.body.contains("verdict")) refusal["verdict"] = answer.body["verdict"];
    return {answer.status, refusal};
  }
  answer.body["note"] =
      "the check is still running; the landmark is written when it passes: poll the url";
  return answer;
}

}  // namespace lmk::serve
