// The lmk command line end to end: exit codes, one-line errors, JSON output. Runs the real binary.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/support/test_support.h"

namespace lmk {
namespace {

struct CommandResult {
  int exit_code = -1;
  std::string out, err;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class Cli : public ::testing::Test {
 protected:
  // Runs `lmk ARGS` through the shell, capturing stdout and stderr in the scratch directory.
  CommandResult lmk(const std::string& args) {
    const std::string out = dir_.file("stdout"), err = dir_.file("stderr");
    const int status = std::system(
        (std::string("'") + LMK_BINARY + "' " + args + " >'" + out + "' 2>'" + err + "'").c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
  }

  // A bad-input run: exit code 2 and exactly one line on stderr, starting "lmk: error: ".
  void expect_bad_input(const std::string& args, const std::string& problem) {
    SCOPED_TRACE("lmk " + args);
    const CommandResult r = lmk(args);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err.rfind("lmk: error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(problem), std::string::npos) << r.err;
  }

  std::string path(const std::string& name) { return "'" + dir_.file(name) + "'"; }

  test::ScratchDir dir_;
};

TEST_F(Cli, HelpAndVersion) {
  const CommandResult help = lmk("--help");
  EXPECT_EQ(help.exit_code, 0);
  for (const char* sub : {"info", "convert", "gen"})
    EXPECT_NE(help.out.find(sub), std::string::npos);
  const CommandResult version = lmk("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.out.rfind("lmk 0.", 0), 0u) << version.out;
  EXPECT_NE(version.out.find("OpenVDB"), std::string::npos);
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
