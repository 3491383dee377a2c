// SPDX-License-Identifier: BSD-3-Clause
// lmk serve's JSON API over HTTP, endpoint by endpoint, each with its bad inputs (docs/serve.md).
#include <filesystem>
#include <future>

#include "lmk/geometry/cloud_io.h"
#include "lmk/landmark/box_guess.h"
#include "lmk/landmark/capture_views.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/pbd/internal/plan_json.h"
#include "lmk/pbd/plan.h"
#include "lmk/pr2/simulated_pr2.h"
#include "lmk/search/internal/find_result_json.h"
#include "tests/serve/serve_fixture.h"

namespace lmk::test {
namespace {

namespace fs = std::filesystem;

TEST_F(ServeTest, InfoNamesTheMethodsMetricsAndSettings) {
  start();
  const Reply r = get("/api/info");
  ASSERT_EQ(r.status, 200) << r.text;
  EXPECT_EQ(r.body["methods"], nlohmann::json(search_methods()));
  EXPECT_EQ(r.body["metrics"], nlohmann::json(error_metric_names()));
  EXPECT_EQ(r.body["setting_keys"], nlohmann::json(find_setting_keys()));
  EXPECT_TRUE(r.body["base_frame"].get<bool>());
}

TEST_F(ServeTest, ScenesAreListedDescribedAndSentAsPoints) {
  start();
  const PointCloud cloud = read_cloud(scene_file);
  const Reply list = get("/api/scenes");
  ASSERT_EQ(list.status, 200);
  ASSERT_EQ(list.body["scenes"].size(), 2u);
  EXPECT_EQ(list.body["scenes"][0]["name"], "tabletop.pcd");
  EXPECT_EQ(list.body["scenes"][0]["points"], cloud.size());

  const Reply scene = get("/api/scenes/1");
  ASSERT_EQ(scene.status, 200);
  EXPECT_EQ(scene.body["finite_points"], cloud.count_finite());
  EXPECT_EQ(scene.body["up"], nlohmann::json({0.0, 0.0, 1.0}));
  const Eigen::Vector3d sensor = cloud.T_cloud_sensor.translation();
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(scene.body["sensor"]["position"][i], sensor[i], 1e-12);

  const Reply all = get("/api/scenes/1/cloud");
  ASSERT_EQ(all.status, 200);
  EXPECT_EQ(all.body["points"], cloud.count_finite());
  EXPECT_EQ(all.body["positions"].size(), 3 * cloud.count_finite());
  EXPECT_TRUE(all.body["colors"].is_null());  // the renderer gives no RGB: the page uses height
  // The first finite point, in millimetres.
  for (const Eigen::Vector3f& p : cloud.points) {
    if (!is_finite(p)) continue;
    EXPECT_EQ(all.body["positions"][0], std::lround(p.x() * 1000.0));
    EXPECT_EQ(all.body["positions"][2], std::lround(p.z() * 1000.0));
    break;
  }
  const Reply few = get("/api/scenes/1/cloud?max_points=1000");
  ASSERT_EQ(few.status, 200);
  EXPECT_LE(few.body["points"].get<std::size_t>(), 1000u);
  EXPECT_GT(few.body["points"].get<std::size_t>(), 900u);

  EXPECT_EQ(get("/api/scenes/1/cloud?max_points=0").status, 400);
  EXPECT_EQ(get("/api/scenes/1/cloud?max_points=lots").status, 400);
  const Reply missing = get("/api/scenes/9");
  EXPECT_EQ(missing.status, 404);
  EXPECT_EQ(missing.body["error"], "no scene '9' (scenes: 1, 2)");
}

TEST_F(ServeTest, UploadsAddScenesAndMalformedCloudsAreRefusedWithTheReason) {
  start();
  const Reply up = post_bytes("/api/scenes?name=again.pcd", read_bytes(scene_file));
  ASSERT_EQ(up.status, 201) << up.text;
  EXPECT_EQ(up.body["id"], "3");
  EXPECT_EQ(up.body["source"], "upload");
  EXPECT_EQ(get("/api/scenes/3").body["finite_points"], read_cloud(scene_file).count_finite());

  const Reply garbage = post_bytes("/api/scenes?name=broken.pcd", "VERSION .7\nFIELDS x y\n");
  EXPECT_EQ(garbage.status, 400);
  EXPECT_EQ(garbage.body["error"].get<std::string>().rfind("upload: broken.pcd: ", 0), 0u)
      << garbage.text;
  const std::string pcd = read_bytes(scene_file);
  const Reply truncated = post_bytes("/api/scenes?name=cut.pcd", pcd.substr(0, pcd.size() / 2));
  EXPECT_EQ(truncated.status, 400) << truncated.text;
  EXPECT_EQ(post_bytes("/api/scenes", pcd).status, 400);  // no name
  const Reply format = post_bytes("/api/scenes?name=scene.obj", pcd);
  EXPECT_EQ(format.status, 400);
  EXPECT_NE(format.body["error"].get<std::string>().find(".pcd"), std::string::npos);
  EXPECT_EQ(post_bytes("/api/scenes?name=..%2Fup.pcd", pcd).status, 400);
  EXPECT_EQ(get("/api/scenes").body["scenes"].size(), 3u);  // the refused ones were not added
}

TEST_F(ServeTest, TheGuessIsTheLibrarysBoxGuessAndRefusesAClickOnTheTable) {
  start();
  const PointCloud cloud = read_cloud(scene_file);
  // The carton's visible point nearest its centre.
  const Eigen::Vector3d centre = carton_box().center();
  Eigen::Vector3d click = Eigen::Vector3d::Constant(1e9);
  for (const Eigen::Vector3f& p : cloud.points) {
    if (is_finite(p) && (p.cast<double>() - centre).norm() < (click - centre).norm()) {
      click = p.cast<double>();
    }
  }
  const Reply r =
      post("/api/guess", {{"scene", "1"}, {"point", {click.x(), click.y(), click.z()}}});
  ASSERT_EQ(r.status, 200) << r.text;
  const BoxGuess expected = guess_box(cloud, click);
  EXPECT_EQ(r.body["box"], box_json(expected.box));
  EXPECT_EQ(r.body["object_points"], expected.object.size());

  // The table top far from any object.
  const Reply table = post("/api/guess", {{"scene", "1"}, {"point", {0.3, -0.3, 0.7}}});
  EXPECT_EQ(table.status, 422) << table.text;
  EXPECT_FALSE(table.body["error"].get<std::string>().empty());
  EXPECT_EQ(post("/api/guess", {{"scene", "1"}}).status, 400);
  EXPECT_EQ(post("/api/guess", {{"scene", "1"}, {"point", {1, 2}}}).status, 400);
  EXPECT_EQ(post("/api/guess", {{"scene", "7"}, {"point", {1, 2, 3}}}).status, 404);
  EXPECT_EQ(post("/api/guess", {{"scene", "1"}, {"point", {1, 2, 3}}, {"margin", -1}}).status, 400);
  EXPECT_EQ(post_text("/api/guess", "{scene: 1").status, 400);
  EXPECT_EQ(post_text("/api/guess", "[1, 2]").status, 400);
}

TEST_F(ServeTest, TheVerdictComesBeforeTheFileAndTheCaptureIsWrittenIntoTheLibrary) {
  start();
  const nlohmann::json box = box_json(carton_box());
  // The check writes nothing. The carton of this scene looks like the table's square leg from
  // this camera (scripts/tabletop-demo.sh): not distinctive, and each look-alike is given.
  const nlohmann::json verdict =
      run("/api/check", {{"scene", "1"}, {"name", "carton"}, {"box", box}});
  EXPECT_TRUE(verdict["checked"].get<bool>());
  EXPECT_TRUE(verdict["found_itself"].get<bool>());
  EXPECT_EQ(verdict["distinctive"].get<bool>(), verdict["other_instances"].empty());
  EXPECT_FALSE(verdict["message"].get<std::string>().empty());
  // The slide check, apart from the look-alikes: the carton's corner fixes every direction.
  EXPECT_TRUE(verdict["slides"].is_array());
  EXPECT_TRUE(verdict["slides"].empty()) << verdict["slides"];
  EXPECT_FALSE(fs::exists(fs::path(landmarks_dir) / "carton.lmk"));

  // With "check", a landmark that is not distinctive is not written: 409 and the verdict.
  if (!verdict["distinctive"].get<bool>()) {
    // The check runs as a job: a request waits for it at most kMaxRequestWait, then polls.
    const Reply refused = until_finished(
        *client, post("/api/landmarks",
                      {{"scene", "1"}, {"name", "carton"}, {"box", box}, {"check", true}}));
    EXPECT_EQ(refused.status, 409) << refused.text;
    EXPECT_EQ(without_times(refused.body["verdict"]), without_times(verdict));
    EXPECT_FALSE(fs::exists(fs::path(landmarks_dir) / "carton.lmk"));
  }
  // The user overrides the verdict: saved, and equal to a capture of the same box.
  const Reply saved = post("/api/landmarks", {{"scene", "1"}, {"name", "carton"}, {"box", box}});
  ASSERT_EQ(saved.status, 201) << saved.text;
  EXPECT_EQ(saved.body["file"], "carton.lmk");
  CaptureSettings base;
  base.base_frame = true;
  const Landmark expected = capture(read_cloud(scene_file), carton_box(), "carton", base);
  const Landmark written = load_landmark((fs::path(landmarks_dir) / "carton.lmk").string());
  EXPECT_EQ(written.points.size(), expected.points.size());
  EXPECT_EQ(saved.body["points"], expected.points.size());
  const Reply list = get("/api/landmarks");
  ASSERT_EQ(list.body["landmarks"].size(), 1u);
  EXPECT_EQ(list.body["landmarks"][0]["name"], "carton");
  const Reply one = get("/api/landmarks/carton");
  ASSERT_EQ(one.status, 200);
  EXPECT_EQ(one.body["positions"].size(), expected.points.size());

  // A second capture under the name is refused unless it replaces it.
  const nlohmann::json again = {{"scene", "1"}, {"name", "carton"}, {"box", box}};
  EXPECT_EQ(post("/api/landmarks", again).status, 409);
  nlohmann::json replace = again;
  replace["overwrite"] = true;
  EXPECT_EQ(post("/api/landmarks", replace).status, 201);

  // Bad inputs: name, box, scene; a box around nothing is the capture's own refusal (422).
  nlohmann::json bad = again;
  bad["name"] = "../carton";
  EXPECT_EQ(post("/api/landmarks", bad).status, 400);
  bad = again;
  bad["box"]["size"] = {0.1, -0.1, 0.1};
  EXPECT_EQ(post("/api/landmarks", bad).status, 400);
  bad = again;
  bad["box"]["quaternion"] = {1, 1, 0, 0};
  EXPECT_EQ(post("/api/landmarks", bad).status, 400);
  bad = again;
  bad["name"] = "air";
  bad["box"]["position"] = {5.0, 5.0, 5.0};
  const Reply empty = post("/api/landmarks", bad);
  EXPECT_EQ(empty.status, 422) << empty.text;
  EXPECT_FALSE(fs::exists(fs::path(landmarks_dir) / "air.lmk"));
  EXPECT_EQ(get("/api/landmarks/air").status, 404);
  EXPECT_EQ(get("/api/landmarks/..%2Fcarton").status, 400);
}

TEST_F(ServeTest, FindGivesWhatTheLibraryFindsWithTheRejectedCandidatesAndProgress) {
  start();
  capture_carton();
  const Landmark carton = load_landmark((fs::path(landmarks_dir) / "carton.lmk").string());
  const FindResult expected = find_landmark(read_cloud(scene_file), carton, scene_settings());
  const nlohmann::json result = run("/api/find", {{"scene", "1"}, {"rejected", true}});
  ASSERT_EQ(result["results"].size(), 1u);
  const nlohmann::json& r = result["results"][0];
  EXPECT_EQ(r["landmark"], "carton");
  EXPECT_EQ(without_times(r["matches"]),
            without_times(detail::find_result_to_json(expected)["matches"]));
  EXPECT_EQ(r["rejected"].size(), expected.rejected.size());
  for (std::size_t i = 0; i < expected.rejected.size(); ++i) {
    EXPECT_EQ(r["rejected"][i]["reason"], to_string(expected.rejected[i].reason));
  }
  EXPECT_EQ(r["error_unit"], "m");

  // Without waiting: 202 and the job, polled until done, with its progress at the end.
  const Reply started = post("/api/find", {{"scene", "1"}, {"landmarks", {"carton"}}});
  ASSERT_EQ(started.status, 202) << started.text;
  const std::string job = started.body["job"];
  EXPECT_EQ(started.body["url"], "/api/jobs/" + job);
  Reply polled;
  do {
    polled = get("/api/jobs/" + job + "?wait=1");
    ASSERT_EQ(polled.status, 200);
  } while (polled.body["state"] != "done" && polled.body["state"] != "failed");
  EXPECT_EQ(polled.body["state"], "done");
  EXPECT_EQ(polled.body["progress"]["fraction"], 1.0);
  EXPECT_EQ(without_times(polled.body["result"]["results"][0]["matches"]),
            without_times(r["matches"]));

  // Settings in their wire form, nested by stage in SI units (the form the answer holds); bad ones
  // are refused naming the field.
  const nlohmann::json paper = run(
      "/api/find",
      {{"scene", "1"}, {"settings", {{"selection", {{"metric", "paper"}, {"threshold", 0.004}}}}}});
  EXPECT_EQ(paper["results"][0]["stats"]["metric"], "paper");
  EXPECT_EQ(paper["results"][0]["stats"]["threshold"], 0.004);
  const Reply unknown =
      post("/api/find", {{"scene", "1"}, {"settings", {{"fast", {{"max_tilted", 3}}}}}});
  EXPECT_EQ(unknown.status, 400);
  // Issue #61, finding 9: no more names than the library holds landmarks, counted before any is
  // read (100,000 names were read whole).
  const Reply many = post(
      "/api/find", {{"scene", "1"}, {"landmarks", std::vector<std::string>(100000, "carton")}});
  EXPECT_EQ(many.status, 400);
  EXPECT_NE(many.text.find("find: landmarks: 100000 names; at most"), std::string::npos)
      << many.text;
  EXPECT_NE(
      unknown.body["error"].get<std::string>().find("settings.fast: unknown setting 'max_tilted'"),
      std::string::npos)
      << unknown.body;
  // The answer's settings are the wire form: sent back, they give the same search.
  const nlohmann::json again = run("/api/find", {{"scene", "1"}, {"settings", paper["settings"]}});
  EXPECT_EQ(again["results"][0]["stats"]["threshold"], 0.004);
  EXPECT_EQ(again["settings"], paper["settings"]);
  EXPECT_EQ(post("/api/find", {{"scene", "1"}, {"settings", {{"selection", {{"threshold", -1}}}}}})
                .status,
            400);
  EXPECT_EQ(post("/api/find", {{"scene", "1"}, {"settings", {{"method", "magic"}}}}).status, 400);
  EXPECT_EQ(post("/api/find", {{"scene", "1"}, {"settings", 3}}).status, 400);
  EXPECT_EQ(post("/api/find", {{"scene", "1"}, {"landmarks", {"cup"}}}).status, 404);
  EXPECT_EQ(post("/api/find", {{"scene", "1"}, {"landmarks", "carton"}}).status, 400);
  EXPECT_EQ(post("/api/find", {{"scene", "1"}, {"wait", "yes"}}).status, 400);
  EXPECT_EQ(get("/api/jobs/job-999").status, 404);
  EXPECT_EQ(get("/api/jobs/" + job + "?wait=soon").status, 400);
}

// "Add a view" (issue #35): the capture's further scenes are registered onto its first and fused,
// as `lmk capture A B` fuses them (place_views, then capture_views): the same landmark, point for
// point. A view that cannot join it is refused with the reason.
TEST_F(ServeTest, AddingAViewFusesItAsLmkCaptureDoes) {
  // The tabletop seen again with the camera turned 25 degrees about the vertical through the
  // carton, in the same (world) frame, as a robot's head turning.
  const Box box = carton_box();
  Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
  turn.translate(box.center())
      .rotate(Eigen::AngleAxisd(25.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()))
      .translate(-box.center());
  DepthSensorSettings sensor;
  sensor.seed = 2;
  const std::string side_file = dir.file("tabletop_side.pcd");
  write_cloud(side_file, render_depth(tabletop.mesh, turn * tabletop.T_world_sensor, sensor));
  serve::ServeSettings settings;
  settings.scenes = {scene_file, side_file, robot_scene_file};
  start(settings);

  const Reply saved =
      post("/api/landmarks",
           {{"scene", "1"}, {"views", {"2"}}, {"name", "carton"}, {"box", box_json(box)}});
  ASSERT_EQ(saved.status, 201) << saved.text;
  EXPECT_EQ(saved.body["views"], 2);
  ASSERT_EQ(saved.body["registrations"].size(), 1u);
  EXPECT_EQ(saved.body["registrations"][0]["view"], 2);
  EXPECT_GT(saved.body["registrations"][0]["overlap"].get<double>(), 0.5);

  const PointCloud first = read_cloud(scene_file), side = read_cloud(side_file);
  CaptureSettings base;
  base.base_frame = true;
  const Landmark expected =
      capture_views(place_views({&first, &side}, box, ViewPlacement{}), box, "carton", base);
  const Landmark written = load_landmark((fs::path(landmarks_dir) / "carton.lmk").string());
  ASSERT_EQ(written.view_count(), 2u);
  EXPECT_EQ(written.points.points, expected.points.points);
  EXPECT_EQ(written.point_views, expected.point_views);
  EXPECT_EQ(written.view_origins, expected.view_origins);

  // The check takes the views too, and says how each was registered.
  const nlohmann::json verdict =
      run("/api/check", {{"scene", "1"}, {"views", {"2"}}, {"name", "c"}, {"box", box_json(box)}});
  EXPECT_EQ(verdict["views"], 2);
  EXPECT_EQ(verdict["registrations"].size(), 1u);

  // The frame moved 0.9 m does not show the carton where the first frame has it, whatever the
  // registration makes of the room's planes: refused with the reason, naming the view.
  const Reply apart =
      post("/api/landmarks",
           {{"scene", "1"}, {"views", {"3"}}, {"name", "apart"}, {"box", box_json(box)}});
  EXPECT_EQ(apart.status, 422) << apart.text;
  EXPECT_NE(apart.text.find("view 2"), std::string::npos) << apart.text;
  EXPECT_FALSE(fs::exists(fs::path(landmarks_dir) / "apart.lmk"));
  EXPECT_EQ(post("/api/landmarks",
                 {{"scene", "1"}, {"views", {"9"}}, {"name", "x"}, {"box", box_json(box)}})
                .status,
            404);
  EXPECT_EQ(post("/api/landmarks", {{"scene", "1"},
                                    {"views", {"2"}},
                                    {"poses", {1, 2}},
                                    {"name", "x"},
                                    {"box", box_json(box)}})
                .status,
            400);
}

TEST_F(ServeTest, FindWithoutLandmarksSaysToCaptureOne) {
  start();
  const Reply r = post("/api/find", {{"scene", "1"}});
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.body["error"].get<std::string>().find("capture one"), std::string::npos);
}

TEST_F(ServeTest, TenConcurrentSearchesGiveTheResultsOfTenSequentialOnes) {
  start();
  capture_carton();
  // Ten different searches (ten seeds), first one after the other, then all at once.
  const auto request = [](int seed) {
    return nlohmann::json{
        {"scene", "1"}, {"settings", {{"sampling", {{"seed", seed}}}}}, {"rejected", true}};
  };
  std::vector<nlohmann::json> sequential;
  for (int seed = 0; seed < 10; ++seed) {
    sequential.push_back(without_times(run("/api/find", request(seed))));
  }
  std::vector<std::future<nlohmann::json>> concurrent;
  for (int seed = 0; seed < 10; ++seed) {
    concurrent.push_back(std::async(std::launch::async, [this, seed, &request] {
      const auto own = new_client();  // one connection each, as ten pages would
      nlohmann::json body = request(seed);
      body["wait"] = true;
      const Reply r =
          until_finished(*own, reply_of(own->Post("/api/find", body.dump(), "application/json")));
      if (r.status != 200) return nlohmann::json();
      return without_times(r.body["result"]);
    }));
  }
  // The page stays answered while they run.
  EXPECT_EQ(get("/api/scenes").status, 200);
  for (int seed = 0; seed < 10; ++seed) {
    EXPECT_EQ(concurrent[seed].get(), sequential[seed]) << "seed " << seed;
  }
}

TEST_F(ServeTest, ProgramsArePlannedAsOnTheRobotAndTheirFilesStayInTheirDirectories) {
  start();
  capture_carton();
  // A program reaching 15 cm beside the carton, its landmark file beside it; one whose landmark
  // file lies outside the served directories; and a file that is no program.
  fs::copy_file(fs::path(landmarks_dir) / "carton.lmk", fs::path(programs_dir) / "carton.lmk");
  Program reach;
  reach.name = "reach carton";
  reach.landmarks.emplace_back("carton", "carton.lmk");
  ProgramStep step;
  step.right = ArmTarget{"carton", Eigen::Isometry3d(Eigen::Translation3d(-0.15, 0.0, 0.05)),
                         GripperAction::kOpen};
  reach.steps.push_back(step);
  save_program((fs::path(programs_dir) / "reach.json").string(), reach);
  fs::create_directories(dir.file("outside"));
  fs::copy_file(fs::path(landmarks_dir) / "carton.lmk", dir.file("outside/carton.lmk"));
  Program escape = reach;
  escape.landmarks[0].file = "../outside/carton.lmk";
  save_program((fs::path(programs_dir) / "escape.json").string(), escape);
  write_text((fs::path(programs_dir) / "notes.json").string(), "{\"not\": \"a program\"}");

  const Reply list = get("/api/programs");
  ASSERT_EQ(list.status, 200);
  ASSERT_EQ(list.body["programs"].size(), 3u);
  EXPECT_EQ(list.body["programs"][0]["name"], "escape");
  EXPECT_TRUE(list.body["programs"][1].contains("error"));  // notes: listed, with the reason
  EXPECT_EQ(list.body["programs"][2]["steps"], 1);
  const Reply shown = get("/api/programs/reach");
  ASSERT_EQ(shown.status, 200);
  EXPECT_EQ(shown.body["program"], nlohmann::json::parse(program_to_json(reach)));

  // Planned on each scene exactly as lmk::plan plans for a PR2 at rest: in the scene in front of
  // the robot, and in the original one, whose table is behind it (the landmark is not found).
  for (const std::string id : {"2", "1"}) {
    const nlohmann::json result = run("/api/programs/reach/plan", {{"scene", id}});
    SimulatedPr2 robot(Pr2Kinematics(RobotModel::pr2(), 0.0));
    ASSERT_TRUE(robot.configure().ok() && robot.activate().ok());
    JointState start_state;
    robot.read_joint_state(start_state);
    PlanSettings settings;
    settings.find = scene_settings();
    const Plan expected = plan(reach, load_program_landmarks(reach, programs_dir),
                               read_cloud(id == "2" ? robot_scene_file : scene_file),
                               robot.kinematics(), start_state, settings);
    EXPECT_EQ(without_times(result["plan"]), without_times(detail::plan_to_json(expected)))
        << "scene " << id;
    ASSERT_EQ(result["targets"].size(), 1u);
    EXPECT_EQ(result["targets"][0]["pose"].is_null(), expected.landmarks.empty()) << id;
  }

  // Issue #60: with collisions, every motion checked as lmk pbd plan --check-collisions checks it;
  // each arm's swept tool path comes back for the page to draw, from where the arm stood.
  // A step in the base frame ahead of the right shoulder, above the table; one into the table's
  // shadow is refused naming what the forearm would touch, where.
  const auto reach_to = [&](const std::string& name, const Eigen::Vector3d& p) {
    Program ahead = reach;
    ahead.name = name;
    ahead.steps[0].right =
        ArmTarget{kBaseFrame, Eigen::Isometry3d(Eigen::Translation3d(p)), GripperAction::kOpen};
    save_program((fs::path(programs_dir) / (name + ".json")).string(), ahead);
  };
  reach_to("low", {0.55, -0.19, 0.75});
  const nlohmann::json low = run("/api/programs/low/plan", {{"scene", "2"}, {"collisions", true}});
  ASSERT_EQ(low["plan"]["refusal"]["kind"], "collision") << low.dump();
  EXPECT_EQ(low["plan"]["refusal"]["contact"]["where"].size(), 3u);
  EXPECT_TRUE(low["paths"].empty());
  reach_to("ahead", {0.55, -0.19, 1.05});
  const nlohmann::json checked =
      run("/api/programs/ahead/plan", {{"scene", "2"}, {"collisions", true}});
  ASSERT_FALSE(checked["plan"]["steps"].empty()) << checked.dump();
  for (const auto& step : checked["plan"]["steps"])
    for (const auto& arm : step["arms"]) EXPECT_FALSE(arm["clearance_m"].is_null()) << arm.dump();
  ASSERT_EQ(checked["paths"].size(), 1u);
  EXPECT_EQ(checked["paths"][0]["arm"], "right");
  EXPECT_GE(checked["paths"][0]["points"].size(), 2u);
  const nlohmann::json unchecked =
      run("/api/programs/ahead/plan", {{"scene", "2"}, {"collisions", false}});
  for (const auto& step : unchecked["plan"]["steps"])
    for (const auto& arm : step["arms"]) EXPECT_TRUE(arm["clearance_m"].is_null());
  // Checked unless the request says otherwise, as lmk pbd plan.
  const nlohmann::json by_default = run("/api/programs/ahead/plan", {{"scene", "2"}});
  for (const auto& step : by_default["plan"]["steps"])
    for (const auto& arm : step["arms"]) EXPECT_FALSE(arm["clearance_m"].is_null());
  EXPECT_EQ(post("/api/programs/ahead/plan", {{"scene", "2"}, {"padding", 0.5}}).status, 400);

  const Reply outside = post("/api/programs/escape/plan", {{"scene", "2"}});
  EXPECT_EQ(outside.status, 403) << outside.text;
  EXPECT_EQ(post("/api/programs/notes/plan", {{"scene", "2"}}).status, 422);
  EXPECT_EQ(post("/api/programs/none/plan", {{"scene", "2"}}).status, 404);
  EXPECT_EQ(post("/api/programs/reach/plan", {{"scene", "2"}, {"torso", "high"}}).status, 400);
  EXPECT_EQ(get("/api/programs/..%2F..%2Fetc%2Fpasswd").status, 400);
}

// Issue #34, finding 3: a health route, and DELETE /api/jobs/ID over HTTP.
TEST_F(ServeTest, HealthAnswersAndJobsCanBeCancelled) {
  start();
  const Reply health = get("/api/health");
  EXPECT_EQ(health.status, 200);
  EXPECT_EQ(health.body["ok"], true);
  const auto missing = client->Delete("/api/jobs/job-999");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
  capture_carton();
  const Reply started = post("/api/find", {{"scene", "1"}, {"landmarks", {"carton"}}});
  ASSERT_EQ(started.status, 202) << started.text;
  const std::string id = started.body["job"];
  const Reply finished = until_finished(*client, started);
  EXPECT_EQ(finished.status, 200);
  const auto again = client->Delete(("/api/jobs/" + id).c_str());
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 409) << again->body;  // it had finished
}

// Issue #34, finding 3: Ctrl-C took 22 s with a search under way. A search that would run for
// hours, a long poll and a POST waiting on it: stopping the server answers both (the job still
// running, never done), the server and its pool stop, and the test ends.
TEST_F(ServeTest, StoppingDoesNotWaitForASearchUnderWay) {
  start();
  capture_carton();
  const nlohmann::json endless = {{"scene", "1"},
                                  {"landmarks", {"carton"}},
                                  {"settings",
                                   {{"method", "reference"},
                                    {"reference", {{"sample_fraction", 1}}},
                                    {"sampling", {{"max_seeds", 1000000}}}}}};
  const Reply started = post("/api/find", endless);
  ASSERT_EQ(started.status, 202) << started.text;
  const std::string url = "/api/jobs/" + started.body["job"].get<std::string>();
  while (get(url).body.value("state", "") != "running") std::this_thread::yield();
  auto poll = std::async(std::launch::async,
                         [&] { return reply_of(new_client()->Get((url + "?wait=10").c_str())); });
  nlohmann::json waiting = endless;
  waiting["wait"] = true;
  auto post_waiting = std::async(std::launch::async, [&] {
    return reply_of(new_client()->Post("/api/find", waiting.dump(), "application/json"));
  });
  server->stop();
  thread.join();
  // Each got an answer or a closed connection; neither waited for the search.
  const Reply p = poll.get(), w = post_waiting.get();
  EXPECT_FALSE(p.body.is_object() && p.body.value("state", "") == "done") << p.text;
  EXPECT_NE(w.status, 200) << w.text;
}

}  // namespace
}  // namespace lmk::test
