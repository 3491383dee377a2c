// SPDX-License-Identifier: BSD-3-Clause
// The lmk command line end to end: exit codes, one-line errors, JSON output. Runs the real binary.

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "lmk/geometry/pose.h"
#include "tests/cli/cli_fixture.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

using test::CommandResult;

TEST_F(Cli, HelpAndVersion) {
  const CommandResult help = lmk("--help");
  EXPECT_EQ(help.exit_code, 0);
  for (const char* sub : {"info", "convert", "gen", "capture", "find", "landmark", "robot", "pbd"})
    EXPECT_NE(help.out.find(sub), std::string::npos);
  const CommandResult version = lmk("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.out.rfind("lmk 0.", 0), 0u) << version.out;
  EXPECT_NE(version.out.find("OpenVDB"), std::string::npos);
}

// lmk metrics: the registry as a table and as JSON, each metric with its own threshold and prune
// bound, in its own unit; an unknown name refused in one line.
TEST_F(Cli, MetricsListsTheRegistryWithWhatEachSaysOfItself) {
  const CommandResult table = lmk("metrics");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  for (const char* line : {"visibility   threshold 6.0 mm", "prunes at 15.0 mm",
                           "sensor       threshold 1.00 sigma", "prunes at 2.00 sigma"}) {
    EXPECT_NE(table.out.find(line), std::string::npos) << line << "\n" << table.out;
  }
  const CommandResult json = lmk("metrics sensor paper --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  ASSERT_EQ(j.size(), 2u);
  EXPECT_EQ(j[0].at("name"), "sensor");
  EXPECT_EQ(j[0].at("error_unit"), "sd");
  EXPECT_EQ(j[0].at("noise_normalised"), true);
  EXPECT_DOUBLE_EQ(j[0].at("prune_bound").get<double>(), 2.0);
  EXPECT_EQ(j[1].at("name"), "paper");
  EXPECT_EQ(j[1].at("error_unit"), "m");
  EXPECT_DOUBLE_EQ(j[1].at("prune_bound").get<double>(), 2.5 * 0.0055);
  expect_bad_input("metrics nope", "unknown error metric 'nope'");
}

TEST_F(Cli, UsageErrors) {
  expect_bad_input("", "A subcommand is required");
  expect_bad_input("frobnicate", "frobnicate");
  expect_bad_input("info", "file is required");
  expect_bad_input("convert " + path("a.pcd") + " " + path("b.pcd") + " --encoding lz4", "lz4");
}

TEST_F(Cli, BadFiles) {
  expect_bad_input("info " + path("missing.pcd"), "no such file");
  test::write_text(dir_.file("garbage.pcd"), "garbage\n");
  expect_bad_input("info " + path("garbage.pcd"), "not a valid PCD file");
  test::write_text(dir_.file("cloud.obj"), "v 1 2 3\n");
  expect_bad_input("info " + path("cloud.obj"), "unknown extension");
  expect_bad_input("convert " + path("missing.pcd") + " " + path("out.ply"), "no such file");
}

// A file name is the user's: lmk info shows its control and bidirectional characters escaped,
// never sent to the terminal (issue #61, finding 8).
TEST_F(Cli, InfoEscapesTheFileName) {
  const std::string name =
      "a\x1b]0;title\x07\xe2\x80\xae"
      "dcp.xyz";
  {
    std::ofstream out(dir_.file(name));
    out << "0 0 1\n1 0 1\n0 1 1\n";
  }
  const CommandResult info = lmk("info " + path(name));
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_EQ(info.out.find('\x1b'), std::string::npos);
  EXPECT_EQ(info.out.find('\x07'), std::string::npos);
  EXPECT_EQ(info.out.find("\xe2\x80\xae"), std::string::npos);
  EXPECT_NE(info.out.find("a\\x1b]0;title\\x07\\xe2\\x80\\xaedcp.xyz"), std::string::npos)
      << info.out;
}

TEST_F(Cli, GenInfoConvert) {
  ASSERT_EQ(lmk("gen " + path("scene.pcd") + " --seed 4").exit_code, 0);
  const CommandResult info = lmk("info " + path("scene.pcd") + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto j = nlohmann::json::parse(info.out);
  std::vector<std::string> keys;
  for (const auto& item : j.items()) keys.push_back(item.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"bounds", "fields", "finite_points", "height", "points",
                                            "sensor_origin", "width"}));
  EXPECT_EQ(j["points"], 307200);
  EXPECT_EQ(j["width"], 640);
  EXPECT_EQ(j["height"], 480);
  EXPECT_GT(j["finite_points"].get<int>(), 100000);
  EXPECT_LT(j["finite_points"].get<int>(), 307200);
  EXPECT_EQ(j["fields"], (std::vector<std::string>{"x", "y", "z"}));
  for (int a = 0; a < 3; ++a) EXPECT_LE(j["bounds"]["min"][a], j["bounds"]["max"][a]);
  EXPECT_GT(j["sensor_origin"][2].get<double>(), 1.0);  // the head-height sensor

  EXPECT_EQ(lmk("convert " + path("scene.pcd") + " " + path("scene.ply")).exit_code, 0);
  EXPECT_EQ(
      lmk("convert " + path("scene.ply") + " " + path("back.pcd") + " --encoding ascii").exit_code,
      0);
  const auto back = nlohmann::json::parse(lmk("info " + path("back.pcd") + " --json").out);
  EXPECT_EQ(back, j);  // nothing lost through PLY and ASCII PCD, sensor origin included

  expect_bad_input("convert " + path("scene.pcd") + " " + path("scene.obj"), "unknown extension");
  EXPECT_FALSE(std::filesystem::exists(dir_.file("scene.obj")));
}

// Numbers that would wrap around in an unsigned field, or poison a computation, are refused.
TEST_F(Cli, NegativeCountsAndNonFiniteValuesAreRefused) {
  expect_bad_input("gen " + path("x.pcd") + " --seed -1",
                   "--seed: '-1' is not a non-negative whole number");
  expect_bad_input("bench --reference-seeds -2",
                   "--reference-seeds: '-2' is not a non-negative whole number");
  expect_bad_input("robot fk --group right_arm --joints nan 0 0 0 0 0 0",
                   "--joints: 'nan' is not a finite number");
  expect_bad_input("robot ik --position 0.5 inf 1 --rpy 0 0 0",
                   "--position: 'inf' is not a finite number");
  EXPECT_FALSE(std::filesystem::exists(dir_.file("x.pcd")));
}

TEST_F(CliLandmark, CaptureShowExportImportFind) {
  const CommandResult captured = lmk("capture " + path("scene.pcd") + " " + carton_ +
                                     " --name carton -o " + path("carton.lmk"));
  ASSERT_EQ(captured.exit_code, 0) << captured.err;
  // The distinctiveness check: seen from this camera, the table's square leg under the table top
  // (a 7 x 7 cm post at x = y = 0) has the carton's visible faces, and capture names the places:
  // one or more heights along the post (and, as the search finds them, other right-angled edges
  // such as the table top's), never the carton itself.
  EXPECT_NE(captured.err.find("'carton' also matches"), std::string::npos) << captured.err;
  const std::regex place(R"(at (-?[0-9.]+) (-?[0-9.]+) (-?[0-9.]+) m)");
  int on_the_leg = 0;
  for (std::sregex_iterator it(captured.err.begin(), captured.err.end(), place), end; it != end;
       ++it) {
    const Eigen::Vector2d xy(std::stod((*it)[1]), std::stod((*it)[2]));
    on_the_leg += xy.norm() < 0.01 ? 1 : 0;
    EXPECT_GT((xy - Eigen::Vector2d(-0.301, 0.236)).norm(), 0.05) << it->str();
  }
  EXPECT_GE(on_the_leg, 1) << captured.err;
  const CommandResult unchecked = lmk("capture " + path("scene.pcd") + " " + carton_ +
                                      " --name carton -o " + path("unchecked.lmk") + " --no-check");
  ASSERT_EQ(unchecked.exit_code, 0) << unchecked.err;
  EXPECT_EQ(unchecked.err.find("also matches"), std::string::npos);
  const CommandResult show = lmk("landmark show " + path("carton.lmk"));
  EXPECT_EQ(show.exit_code, 0);
  EXPECT_NE(show.out.find("carton"), std::string::npos);
  EXPECT_NE(show.out.find("format         lmk 5"), std::string::npos);
  EXPECT_NE(show.out.find("voxels observed free"), std::string::npos);
  ASSERT_EQ(lmk("landmark export " + path("carton.lmk") + " " + path("exported")).exit_code, 0);
  ASSERT_EQ(lmk("landmark import " + path("exported") + " " + path("again.lmk")).exit_code, 0);
  // The same landmark, but for its empty space: an import has no capture scene, and sees free
  // only the space in front of the landmark's own points.
  const auto without_empty_space = [](std::string text) {
    const std::size_t at = text.find("empty space");
    return at == std::string::npos ? text : text.erase(at, text.find('\n', at) - at);
  };
  EXPECT_EQ(without_empty_space(lmk("landmark show " + path("again.lmk")).out),
            without_empty_space(show.out));

  const CommandResult found =
      lmk("find " + path("scene.pcd") + " " + path("carton.lmk") + " --max-seeds 150 --json -");
  ASSERT_EQ(found.exit_code, 0) << found.err;
  const auto j = nlohmann::json::parse(found.out);
  ASSERT_GE(j["matches"].size(), 1u);
  const auto& best = j["matches"][0];
  EXPECT_NEAR(best["position"][0].get<double>(), -0.301, 0.005);
  EXPECT_NEAR(best["position"][1].get<double>(), 0.236, 0.005);
  EXPECT_NEAR(best["position"][2].get<double>(), 0.826, 0.005);
  EXPECT_EQ(best["quaternion"].size(), 4u);
  EXPECT_LT(best["error"].get<double>(), 0.0055);
  for (const char* term :
       {"scene_to_landmark_sum", "scene_to_landmark_count", "landmark_to_scene_sum",
        "landmark_to_scene_count", "scene_points_in_box", "empty_space_probes",
        "empty_space_violations", "empty_space_violation_mean"}) {
    EXPECT_TRUE(best["terms"].contains(term)) << term;
  }
  EXPECT_GT(best["terms"]["coverage"].get<double>(), 0.9);
  EXPECT_EQ(best["terms"]["empty_space_violations"], 0);
  EXPECT_EQ(j["stats"]["method"], "fast");
  EXPECT_EQ(j["stats"]["metric"], "visibility");
  // Seeds spread one per cell, coarser until they fit the cap: at most 150, and not far below.
  EXPECT_LE(j["stats"]["seeds"].get<int>(), 150);
  EXPECT_GE(j["stats"]["seeds"].get<int>(), 120);
  EXPECT_FALSE(j["stats"].contains("seconds"));  // wall-clock times only with --timings
  const CommandResult timed = lmk("find " + path("scene.pcd") + " " + path("carton.lmk") +
                                  " --max-seeds 150 --timings --json -");
  ASSERT_EQ(timed.exit_code, 0) << timed.err;
  EXPECT_GT(nlohmann::json::parse(timed.out)["stats"]["seconds"].get<double>(), 0.0);
  // --rejected adds the candidates turned down, each with its reason, as many as the stats count.
  EXPECT_FALSE(j.contains("rejected"));
  const CommandResult rejected = lmk("find " + path("scene.pcd") + " " + path("carton.lmk") +
                                     " --max-seeds 150 --rejected --json -");
  ASSERT_EQ(rejected.exit_code, 0) << rejected.err;
  const auto r = nlohmann::json::parse(rejected.out);
  EXPECT_EQ(r["matches"], j["matches"]);
  const auto& stats = r["stats"];
  EXPECT_EQ(r["rejected"].size(), stats["rejected_error"].get<std::size_t>() +
                                      stats["rejected_coverage"].get<std::size_t>() +
                                      stats["rejected_empty_space"].get<std::size_t>() +
                                      stats["rejected_overlap"].get<std::size_t>() +
                                      stats["rejected_undetermined"].get<std::size_t>());
  for (const auto& c : r["rejected"]) {
    const std::string reason = c["reason"];
    EXPECT_TRUE(reason == "error above threshold" || reason == "coverage too low" ||
                reason == "empty space occupied" || reason == "inside a better match" ||
                reason == "shows too little to fix its pose")
        << reason;
    if (reason == "error above threshold") {
      EXPECT_GE(c["error"].get<double>(), stats["threshold"].get<double>());
    }
  }

  const CommandResult table =
      lmk("find " + path("scene.pcd") + " " + path("carton.lmk") + " --max-seeds 150");
  EXPECT_EQ(table.exit_code, 0);
  EXPECT_NE(table.out.find("rank"), std::string::npos);
  EXPECT_NE(table.out.find("error_mm"), std::string::npos);
  EXPECT_NE(table.out.find("coverage"), std::string::npos);
  EXPECT_NE(table.out.find("empty_viol"), std::string::npos);

  // The paper's metric through the reference search prints the paper's terms instead.
  const CommandResult reference = lmk("find " + path("scene.pcd") + " " + path("carton.lmk") +
                                      " --method reference --max-seeds 20");
  EXPECT_EQ(reference.exit_code, 0) << reference.err;
  EXPECT_NE(reference.out.find("reference, metric paper"), std::string::npos) << reference.out;
}

// Leaves below the documented 1 mm floor are refused up front: 10 um made OpenVDB fail inside the
// search ("internal error"), and a capture at it grew without bound.
TEST_F(CliLandmark, LeavesBelowAMillimetreAreRefusedUpFront) {
  expect_bad_input("capture " + path("scene.pcd") + " " + carton_ + " --name c -o " +
                       path("c.lmk") + " --leaf 1e-5",
                   "capture: leaf_size (--leaf-size): 1e-05 must be finite and in [0.001, 0.1]");
  EXPECT_FALSE(std::filesystem::exists(dir_.file("c.lmk")));
  ASSERT_EQ(lmk("capture " + path("scene.pcd") + " " + carton_ + " --name c -o " + path("c.lmk"))
                .exit_code,
            0);
  expect_bad_input("find " + path("scene.pcd") + " " + path("c.lmk") + " --leaf 1e-5",
                   "scene.leaf_size (--leaf-size): 1e-05 must be finite and in [0.001, 0.1]");
  expect_bad_input("find " + path("scene.pcd") + " " + path("c.lmk") + " --coarse-leaf 0.0005",
                   "in [0.001, 0.1]");
}

TEST_F(CliLandmark, BadInputToCaptureAndFind) {
  const std::string scene = path("scene.pcd");
  expect_bad_input(
      "capture " + scene + " --box-center 0 0 0 --box-size 0 0.1 0.1 --name x -o " + path("x.lmk"),
      "sides must be positive");
  expect_bad_input("capture " + scene + " --box-center 9 9 9 --box-size 0.1 0.1 0.1 --name x -o " +
                       path("x.lmk"),
                   "no scene point inside the box");
  expect_bad_input("capture " + scene + " --name x -o " + path("x.lmk"), "--box-center");
  expect_bad_input(
      "capture " + path("missing.pcd") + " " + carton_ + " --name x -o " + path("x.lmk"),
      "no such file");
  test::write_text(dir_.file("empty.xyz"), "# nothing\n");
  expect_bad_input("capture " + path("empty.xyz") + " " + carton_ + " --name x -o " + path("x.lmk"),
                   "none with finite");
  EXPECT_FALSE(std::filesystem::exists(dir_.file("x.lmk")));

  ASSERT_EQ(
      lmk("capture " + scene + " " + carton_ + " --name carton -o " + path("c.lmk")).exit_code, 0);
  expect_bad_input("find " + path("missing.pcd") + " " + path("c.lmk"), "no such file");
  expect_bad_input("find " + path("empty.xyz") + " " + path("c.lmk"), "none with finite");
  expect_bad_input("find " + scene + " " + path("missing.lmk"), "no such file");
  expect_bad_input("find " + scene + " " + scene, "not an lmk landmark file");  // another format
  expect_bad_input("find " + scene + " " + path("c.lmk") + " --metric nope",
                   "selection.metric (--metric): 'nope' must be one of paper, rapid");
  expect_bad_input("find " + scene + " " + path("c.lmk") + " --method magic",
                   "--method: 'magic' must be one of fast, reference");
  expect_bad_input("find " + scene + " " + path("c.lmk") + " --up 0 0 0",
                   "scene.up (--up): must be a finite non-zero vector");
  expect_bad_input("find " + scene + " " + path("c.lmk") + " --orientations sideways",
                   "--orientations: 'sideways' must be one of upright, full");
  expect_bad_input("find " + scene + " " + path("c.lmk") + " --max-tilt 200",
                   "fast.max_tilt (--max-tilt): 200 must be finite and in [0, 180] degrees");
  expect_bad_input("find " + scene + " " + path("c.lmk") + " --max-seeds -3",
                   "--max-seeds: '-3' is not a non-negative whole number");
  expect_bad_input("find " + scene + " " + path("c.lmk") + " --threshold inf",
                   "--threshold: 'inf' is not a finite number");
  expect_bad_input(
      "capture " + scene + " " + carton_ + " --name x -o " + path("x.lmk") +
          " --depth-smoothing 11",
      "capture: depth_smoothing (--depth-smoothing): 11 must be finite and in [0, 10]");
  expect_bad_input("find " + scene + " " + path("c.lmk") + " --depth-smoothing 11",
                   "scene.depth_smoothing (--depth-smoothing): 11 must be");
  expect_bad_input("find " + scene + " " + path("c.lmk") + " --coarse-leaf 0.001",
                   "the coarse leaf (--coarse-leaf, 0.001 m) must be at least the leaf size");
  // Issue #34, finding 2: 10,000,000 threads exited 139 and 100,000,000 "internal error:
  // std::bad_alloc"; a field band of 5 m ran for minutes at 1.3 GB.
  for (const char* threads : {"10000000", "100000000"}) {
    expect_bad_input("find " + scene + " " + path("c.lmk") + " --threads " + threads,
                     "execution.threads (--threads)");
  }
  expect_bad_input("find " + scene + " " + path("c.lmk") + " --field-band 5",
                   "scene.field_band (--field-band): 5 must be finite and in [0.001, 0.2]");
  expect_bad_input("find " + scene + " " + path("c.lmk") + " --field-band 0.15",
                   "must be at most 10 coarse leaves");
  expect_bad_input("eval --threads 100000000", "is not a thread count");
  expect_bad_input("bench --threads 100000000", "is not a thread count");
  expect_bad_input("pbd demo-tasks --threads 100000000", "is not a thread count");
}

// A depth camera's correction (lmk calibrate-depth's file) is undone on the frame read by capture,
// find and convert; one that does not fit the frame, or a bad file, is one line naming the file.
// Issue #47: a scene whose index would not fit the machine is refused in one line before anything
// is built. A million points scattered through a kilometre each need their own distance-field
// nodes: about 70 GB, where they had run until the kernel killed lmk.
TEST_F(CliLandmark, ASceneWhoseIndexWouldNotFitTheMachineIsRefusedUpFront) {
  std::ifstream meminfo("/proc/meminfo");
  double available_gb = 0.0;
  for (std::string key; meminfo >> key;) {
    double kb = 0.0;
    if (key == "MemAvailable:" && meminfo >> kb) available_gb = kb / (1024.0 * 1024.0);
  }
  if (available_gb > 50.0) GTEST_SKIP() << "this machine has " << available_gb << " GB available";
  const std::size_t n = 1'000'000;
  std::ofstream far(dir_.file("far.pcd"), std::ios::binary);
  far << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " << n
      << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << n << "\nDATA binary\n";
  std::uint32_t state = 12345;
  for (std::size_t i = 0; i < 3 * n; ++i) {
    state = state * 1664525u + 1013904223u;  // a fixed sequence, anywhere in +-500 m
    const float v =
        static_cast<float>(state >> 8) / static_cast<float>(1u << 24) * 1000.0f - 500.0f;
    far.write(reinterpret_cast<const char*>(&v), sizeof v);
  }
  far.close();
  ASSERT_EQ(
      lmk("capture " + path("scene.pcd") + " " + carton_ + " --name carton -o " + path("c.lmk"))
          .exit_code,
      0);
  expect_bad_input("find " + path("far.pcd") + " " + path("c.lmk") + " --base-frame",
                   "this machine has available; crop it (--work-volume) or use a coarser leaf");
}

// Issue #48: lmk track follows a landmark through frames (here the same frame three times, and a
// directory of them), a line per frame and landmark, JSON lines, and a summary.
TEST_F(CliLandmark, TrackFollowsALandmarkThroughFramesAndRefusesBadInput) {
  ASSERT_EQ(
      lmk("capture " + path("scene.pcd") + " " + carton_ + " --name carton -o " + path("c.lmk"))
          .exit_code,
      0);
  std::filesystem::create_directories(dir_.file("frames"));
  for (const char* name : {"a.pcd", "b.pcd", "c.pcd"}) {
    std::filesystem::copy_file(dir_.file("scene.pcd"), dir_.file("frames/") + name);
  }
  const CommandResult text = lmk("track " + path("frames") + " " + path("c.lmk"));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("frame 0 a.pcd: 'carton' found at"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("frame 2 c.pcd: 'carton' tracking at"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("tracked 3 frames; per frame median"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("'carton': followed in 2 frames, lost in 0 (0 losses)"),
            std::string::npos)
      << text.out;

  const CommandResult json = lmk("track " + path("scene.pcd") + " " + path("scene.pcd") + " " +
                                 path("c.lmk") + " --json -");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  std::istringstream lines(json.out);
  std::vector<nlohmann::json> records;
  for (std::string line; std::getline(lines, line);) records.push_back(nlohmann::json::parse(line));
  ASSERT_EQ(records.size(), 2u) << json.out;
  EXPECT_EQ(records[0]["state"], "found");
  EXPECT_EQ(records[1]["state"], "tracking");
  EXPECT_FALSE(records[1].contains("seconds"));  // only with --timings
  const std::vector<double> found = records[0]["position"], followed = records[1]["position"];
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(found[a], followed[a], 0.002);

  expect_bad_input("track " + path("scene.pcd") + " " + path("scene.pcd"),
                   "track: give at least one landmark file (.lmk)");
  expect_bad_input("track " + path("c.lmk") + " " + path("c.lmk"), "track: give the frames");
  std::filesystem::create_directories(dir_.file("empty"));
  expect_bad_input("track " + path("empty") + " " + path("c.lmk"), "holds no cloud file");
  // The tracker's settings are described once (TrackSettings::describe()): their flags refuse as
  // the search's do.
  expect_bad_input("track " + path("scene.pcd") + " " + path("c.lmk") + " --follow-margin 5",
                   "track: follow_margin (--follow-margin): 5 must be");
  expect_bad_input(
      "track " + path("scene.pcd") + " " + path("c.lmk") + " --follow-threshold-factor 0.5",
      "track: follow_threshold_factor (--follow-threshold-factor): 0.5 must be");
  expect_bad_input("track " + path("scene.pcd") + " " + path("c.lmk") + " --camera-motion sideways",
                   "--camera-motion: 'sideways' must be one of none, estimated");
}

TEST_F(CliLandmark, EvalTrackScoresTheMovingPresetsSequencesAndRefusesBadInput) {
  // One short sequence without noise: a bottle pushed about, carried once, put down elsewhere.
  const CommandResult gen = lmk("gen --preset moving " + path("moving") +
                                " --types tide_bottle --seeds 1 --frames 12 --no-noise");
  ASSERT_EQ(gen.exit_code, 0) << gen.err;
  EXPECT_NE(gen.out.find("1 landmarks, 1 sequences of 12 frames each"), std::string::npos)
      << gen.out;
  const CommandResult eval =
      lmk("eval-track " + path("moving") + " --json " + path("tracking.json"));
  ASSERT_EQ(eval.exit_code, 0) << eval.err;
  EXPECT_NE(eval.out.find("moving-tide_bottle-1"), std::string::npos) << eval.out;
  EXPECT_NE(eval.out.find("frames in view tracked within 10 mm / 5 degrees"), std::string::npos)
      << eval.out;
  std::ifstream in(dir_.file("tracking.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j["sequences"].size(), 1u);
  const nlohmann::json& s = j["sequences"][0];
  EXPECT_EQ(s["frames"].size(), 12u);
  EXPECT_EQ(s["frames"][0]["state"], "found");
  EXPECT_LE(s["carry_noticed_after"].get<int>(), 1);
  EXPECT_LE(s["refound_after"].get<int>(), 4);
  EXPECT_EQ(s["pose_while_away"], 0);

  expect_bad_input("eval-track " + path("moving") + " --only nothing-like-it",
                   "no sequence's name holds 'nothing-like-it'");
  std::filesystem::remove(dir_.file("moving/sequences.json"));
  expect_bad_input("eval-track " + path("moving"), "holds no sequences");
  expect_bad_input("gen --preset moving " + path("m2") + " --frames 5",
                   "--frames must be 10 to 3000");
  expect_bad_input("gen --preset moving " + path("m2") + " --types chair_corner",
                   "not 'chair_corner'");
  expect_bad_input("gen --preset moving " + path("m2") + " --hard", "--preset moving takes");
}

TEST_F(CliLandmark, DepthCorrectionAppliesToTheFrameReadOrIsRefusedInOneLine) {
  const std::string scene = path("scene.pcd");
  const auto correction = [&](const std::string& name, const std::string& image,
                              const std::string& cells, const std::string& values) {
    test::write_text(dir_.file(name),
                     R"({"format": "lmk-depth-correction", "version": 1, "image": )" + image +
                         R"(, "cells": )" + cells + R"(, "per_metre": )" + values + "}");
    return path(name);
  };
  const std::string none = correction("none.json", "[640, 480]", "[1, 1]", "[0]");
  const std::string far = correction("far.json", "[640, 480]", "[2, 1]", "[0.01, 0.02]");
  const std::string small = correction("small.json", "[4, 3]", "[1, 1]", "[0]");
  const std::string bad = correction("bad.json", "[640, 480]", "[3, 1]", "[0, 0]");

  // No error to undo: the same landmark and the same matches as without the option.
  ASSERT_EQ(lmk("capture " + scene + " " + carton_ + " --name c -o " + path("c.lmk")).exit_code, 0);
  ASSERT_EQ(lmk("capture " + scene + " " + carton_ + " --name c -o " + path("c0.lmk") +
                " --depth-correction " + none)
                .exit_code,
            0);
  const CommandResult plain = lmk("find " + scene + " " + path("c.lmk") + " --json -");
  const CommandResult corrected_none =
      lmk("find " + scene + " " + path("c0.lmk") + " --json - --depth-correction " + none);
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(corrected_none.out, plain.out);
  // An error to undo moves the points: the converted frame differs, point for point.
  ASSERT_EQ(
      lmk("convert " + scene + " " + path("far.xyz") + " --depth-correction " + far).exit_code, 0);
  ASSERT_EQ(lmk("convert " + scene + " " + path("same.xyz")).exit_code, 0);
  EXPECT_NE(slurp(dir_.file("far.xyz")), slurp(dir_.file("same.xyz")));

  expect_bad_input("find " + scene + " " + path("c.lmk") + " --depth-correction " + small,
                   dir_.file("small.json") +
                       ": depth correction: fitted on 4 x 3 images, given a frame of 640 x 480");
  expect_bad_input("capture " + path("same.xyz") + " " + carton_ + " --name x -o " + path("x.lmk") +
                       " --depth-correction " + none,
                   "given an unorganised cloud");
  expect_bad_input("convert " + scene + " " + path("x.pcd") + " --depth-correction " + bad,
                   dir_.file("bad.json") + ": depth correction: 2 values for 3 cells");
  expect_bad_input(
      "find " + scene + " " + path("c.lmk") + " --depth-correction " + path("missing.json"),
      "--depth-correction");
  expect_bad_input("serve " + scene + " --depth-correction " + small,
                   dir_.file("scene.pcd") + ": depth correction: fitted on 4 x 3 images");
  EXPECT_FALSE(std::filesystem::exists(dir_.file("x.lmk")));
  EXPECT_FALSE(std::filesystem::exists(dir_.file("x.pcd")));
}

// lmk calibrate-depth on the real Kinect sequence: a correction file that makes its frames agree
// better than they did, which lmk gen --from-rgbd --depth-correction then applies.
TEST_F(Cli, CalibrateDepthOnTheRealKitchenWritesACorrectionTheImportApplies) {
  LMK_REQUIRE_SHARED_DATA(data);
  const std::string kitchen = "'" + (data / "real" / "redkitchen").string() + "'";
  const CommandResult fit =
      lmk("calibrate-depth " + kitchen + " -o " + path("k.json") + " --every 5 --gap 1 4");
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(dir_.file("k.json")));
  EXPECT_EQ(j["format"], "lmk-depth-correction");
  EXPECT_EQ(j["per_metre"].size(), 48u);
  EXPECT_LT(j["rms_after_m"].get<double>(), j["rms_before_m"].get<double>());
  expect_bad_input("calibrate-depth " + kitchen + " -o " + path("k.txt"), "must end in .json");
  expect_bad_input(
      "calibrate-depth " + kitchen + " -o " + path("k2.json") + " --cells 64 48 --every 25",
      "too few for 3072 cells");
  expect_bad_input("gen " + path("ds") + " --from-rgbd " + kitchen + " --calibrate-depth " +
                       "--depth-correction " + path("k.json"),
                   "excludes");
}

// Outputs and inputs of the wrong kind are refused before any work: a landmark is never written
// under a point-cloud name, and a directory or a pipe is never read as a file.
TEST_F(CliLandmark, WrongKindsOfFilesAreRefusedUpFront) {
  const std::string scene = path("scene.pcd");
  expect_bad_input("capture " + scene + " " + carton_ + " --name c -o " + path("c.pcd"),
                   "--output: '" + dir_.file("c.pcd") + "': a landmark file must end in .lmk");
  EXPECT_FALSE(std::filesystem::exists(dir_.file("c.pcd")));
  std::filesystem::create_directory(dir_.file("box"));
  expect_bad_input(
      "capture " + scene + " --box-json " + path("box") + " --name c -o " + path("c.lmk"),
      "box: is a directory, not a JSON file");
  ASSERT_EQ(::mkfifo(dir_.file("pipe.lmk").c_str(), 0600), 0);
  expect_bad_input("find " + scene + " " + path("pipe.lmk"),
                   "pipe.lmk: is a named pipe, not a landmark file");
  expect_bad_input("landmark import " + path("box") + " " + path("x.xyz"),
                   "a landmark file must end in .lmk");
}

TEST_F(Cli, MilkSceneFromRealData) {
  LMK_REQUIRE_SHARED_DATA(data);
  const CommandResult info =
      lmk("info '" + (data / "pcl/milk_cartoon_all_small_clorox.pcd").string() + "' --json");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["points"], 307200);
  EXPECT_EQ(j["finite_points"], 241407);
  EXPECT_EQ(j["width"], 640);
  EXPECT_EQ(j["height"], 480);
}

}  // namespace
}  // namespace lmk
