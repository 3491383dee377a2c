// SPDX-License-Identifier: BSD-3-Clause
// A metric that only the test suite knows ("nearest", nearest_surface_metric.cpp, loaded as a
// plugin through $LMK_METRIC_PLUGINS) runs through the searches, the server's metric list and the
// real `lmk find`, `lmk eval` and `lmk ablate`, with the pruning it declares. Its own process: the
// metrics registered here would change the registry the other suites test.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <nlohmann/json.hpp>
#include <utility>

#include "lmk/geometry/error.h"
#include "lmk/landmark/capture_views.h"
#include "lmk/search/find_landmark.h"
#include "lmk/search/metrics/error_metrics.h"
#include "lmk/serve/api.h"
#include "tests/landmark/l_shape_scene.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

using namespace test_scenes;

// Every test starts with the plugin named, as a user would name it, before the registry is read.
class PluginEnvironment : public ::testing::Environment {
 public:
  void SetUp() override { ::setenv(kMetricPluginsVariable, LMK_METRIC_PLUGIN, 1); }
};
const auto* const kEnvironment = ::testing::AddGlobalTestEnvironment(new PluginEnvironment);

// The L-shape's scene with its copies, and the landmark captured at the first.
struct LScene {
  LScene()
      : scene(render_scene(kCopies, true)), landmark(capture(scene, box_at(kCopies[0]), "L")) {}
  PointCloud scene;
  Landmark landmark;
};

FindResult find_with(const LScene& l, const std::string& metric) {
  FindSettings s;
  s.selection.metric = metric;
  return find_landmark(l.scene, l.landmark, s);
}

// How many copies of the L `r` found within 1 cm of their boxes' centres.
std::size_t copies_found(const FindResult& r) {
  std::size_t found = 0;
  for (const Eigen::Vector2d& xy : kCopies) {
    for (const Match& m : r.matches) {
      if ((m.box.center() - box_at(xy).center()).norm() < 0.01) {
        ++found;
        break;
      }
    }
  }
  return found;
}

TEST(MetricPlugin, TheRegistryAndTheServerListIt) {
  const std::vector<std::string> names = error_metric_names();
  ASSERT_FALSE(names.empty());
  EXPECT_EQ(names.back(), "nearest");
  EXPECT_EQ(find_error_metric("nearest").default_threshold, 0.004);
  EXPECT_EQ(format_error(0.0031, "nearest"), "3.1 mm");  // the default display: millimetres

  const test::ScratchDir dir;
  serve::ServeSettings settings;
  settings.landmarks_dir = dir.file("landmarks");
  const serve::Api api(settings, dir.path());
  EXPECT_EQ(api.info().body.at("metrics"), nlohmann::json(names));
}

TEST(MetricPlugin, ASearchFindsTheLandmarkWithItAndPrunesByItsOwnBound) {
  const LScene l;
  const FindResult r = find_with(l, "nearest");
  EXPECT_EQ(r.stats.metric, "nearest");
  EXPECT_EQ(r.stats.threshold, 0.004) << "its own default threshold";
  EXPECT_EQ(copies_found(r), kCopies.size());
  for (const Match& m : r.matches) EXPECT_LT(m.error, 0.004);
  // Its coarse score pruned some of the coarse candidates (the look-alikes), not all.
  EXPECT_GT(r.stats.fast.refined, 0u);
  EXPECT_LT(r.stats.fast.refined, r.stats.fast.clusters);
}

// A metric whose coarse score no candidate can pass prunes them all; one without a coarse score
// sends the best-voted ones on unpruned. Neither inherits another metric's bound.
TEST(MetricPlugin, AMetricsPruningIsItsOwn) {
  ErrorMetric hopeless = find_error_metric("nearest");
  hopeless.name = "nearest_hopeless";
  hopeless.coarse_score = [](const CoarseView&) -> CoarseScore {
    return [](const Eigen::Isometry3f&) { return 1.0; };  // 1 m: beyond 3 x 4 mm
  };
  register_error_metric(hopeless);
  ErrorMetric unranked = find_error_metric("nearest");
  unranked.name = "nearest_unranked";
  unranked.coarse_score = nullptr;
  register_error_metric(unranked);

  const LScene l;
  const FindResult none = find_with(l, "nearest_hopeless");
  EXPECT_GT(none.stats.fast.clusters, 0u);
  EXPECT_EQ(none.stats.fast.refined, 0u);
  EXPECT_TRUE(none.matches.empty());

  FindSettings s;
  const FindResult all = find_with(l, "nearest_unranked");
  EXPECT_EQ(all.stats.fast.refined, std::min(all.stats.fast.clusters, s.fast.max_refined));
  // A scale of the bound is the user's: a thousandth of it prunes every candidate of `nearest`.
  s.selection.metric = "nearest";
  s.fast.prune_scale = 1e-3;
  EXPECT_EQ(find_landmark(l.scene, l.landmark, s).stats.fast.refined, 0u);
}

TEST(MetricPlugin, RegistrationRefusesWhatASearchCouldNotUse) {
  ErrorMetric m = find_error_metric("nearest");
  EXPECT_NE(test::error_of([&] { register_error_metric(m); }).find("the name is taken"),
            std::string::npos);
  m.name = "nearest_without_threshold";
  m.default_threshold = 0.0;
  EXPECT_NE(test::error_of([&] { register_error_metric(m); }).find("default threshold"),
            std::string::npos);
  m.default_threshold = 0.004;
  m.evaluate = nullptr;
  EXPECT_NE(test::error_of([&] { register_error_metric(m); }).find("no evaluate"),
            std::string::npos);
  m.name.clear();
  EXPECT_NE(test::error_of([&] { register_error_metric(m); }).find("no name"), std::string::npos);
}

// A plugin's numbers are checked as the settings are, and its words reach a terminal escaped or
// not at all (issue #61, finding 8).
TEST(MetricPlugin, RegistrationRefusesNumbersOutOfRangeAndUnprintableWords) {
  const ErrorMetric nearest = find_error_metric("nearest");
  const auto refused = [](ErrorMetric m, const std::string& why) {
    EXPECT_NE(test::error_of([&] { register_error_metric(m); }).find(why), std::string::npos)
        << why;
  };
  ErrorMetric m = nearest;
  m.name = "nearest_huge";
  m.default_threshold = 1e300;
  refused(m, "at most 1e6");
  m = nearest;
  m.name = "nearest_inf_prune";
  m.prune_ratio = std::numeric_limits<double>::infinity();
  refused(m, "prune ratio must be 1 to 1000");
  m.prune_ratio = 0.5;
  refused(m, "prune ratio must be 1 to 1000");
  m = nearest;
  m.name = "nearest\x1b[2J";
  refused(m, "printable text");
  m = nearest;
  m.name = "nearest_bidi";
  m.description = "a metric \xe2\x80\xae";
  refused(m, "printable text");
  m = nearest;
  m.name = "nearest_scale";
  m.display.scale = std::numeric_limits<double>::quiet_NaN();
  refused(m, "scale must be positive");
}

// The real binary, with the plugin named in its environment (or, `with_plugin` false, unset).
test::CommandResult lmk(const test::ScratchDir& dir, const std::string& args,
                        bool with_plugin = true) {
  const std::string env =
      with_plugin ? std::string(kMetricPluginsVariable) + "='" + LMK_METRIC_PLUGIN + "' "
                  : std::string("env -u ") + kMetricPluginsVariable + " ";
  return test::run_shell(env + "'" + LMK_BINARY + "' " + args, dir);
}

TEST(MetricPlugin, TheCommandLineFindsEvaluatesAndAblatesWithIt) {
  const test::ScratchDir dir;
  const auto quoted = [&](const std::string& name) { return "'" + dir.file(name) + "'"; };
  const std::string data = quoted("data");
  const test::CommandResult gen = lmk(dir, "gen --preset paper --types simple/three_balls " + data);
  ASSERT_EQ(gen.exit_code, 0) << gen.err;

  // lmk find: the three balls, each error under the metric's own threshold, in its unit.
  const test::CommandResult find =
      lmk(dir, "find " + quoted("data/scenes/simple-three_balls-1.pcd") + " " +
                   quoted("data/landmarks/ball.lmk") + " --metric nearest --json -");
  ASSERT_EQ(find.exit_code, 0) << find.err;
  const nlohmann::json found = nlohmann::json::parse(find.out);
  EXPECT_EQ(found.at("stats").at("metric"), "nearest");
  EXPECT_EQ(found.at("error_unit"), "m");
  EXPECT_EQ(found.at("matches").size(), 3u);
  for (const nlohmann::json& m : found.at("matches")) EXPECT_LT(m.at("error").get<double>(), 0.004);

  const test::CommandResult eval =
      lmk(dir, "eval --dataset " + data + " --metric nearest --pairs in-context --json " +
                   quoted("eval.json"));
  ASSERT_EQ(eval.exit_code, 0) << eval.err;
  const nlohmann::json e = nlohmann::json::parse(test::read_bytes(dir.file("eval.json")));
  EXPECT_EQ(e.at("metric"), "nearest");
  EXPECT_EQ(e.at("threshold"), 0.004);
  EXPECT_FALSE(e.at("pairs").empty());

  const test::CommandResult ablate = lmk(
      dir, "ablate --dataset " + data +
               " --pairs in-context --vary metric=visibility,nearest --out " + quoted("ablation"));
  ASSERT_EQ(ablate.exit_code, 0) << ablate.err;
  EXPECT_NE(ablate.out.find("nearest"), std::string::npos) << ablate.out;

  // lmk metrics lists it after the built-in ones, with the bound it declared (3 x 4 mm).
  const test::CommandResult metrics = lmk(dir, "metrics --json");
  ASSERT_EQ(metrics.exit_code, 0) << metrics.err;
  const nlohmann::json listed = nlohmann::json::parse(metrics.out);
  EXPECT_EQ(listed.back().at("name"), "nearest");
  EXPECT_DOUBLE_EQ(listed.back().at("prune_bound").get<double>(), 0.012);

  // A plugin that cannot be loaded, or that registers nothing, is refused in one line.
  for (const auto& [plugin, why] :
       {std::pair<std::string, std::string>{dir.file("missing.so"), "cannot load"},
        {LMK_LIBRARY_WITHOUT_METRICS, "exports no lmk_register_error_metrics()"}}) {
    const test::CommandResult bad = test::run_shell(
        std::string(kMetricPluginsVariable) + "='" + plugin + "' '" + LMK_BINARY + "' metrics",
        dir);
    EXPECT_EQ(bad.exit_code, 2) << plugin;
    EXPECT_EQ(bad.err.rfind("lmk: error: LMK_METRIC_PLUGINS: ", 0), 0u) << bad.err;
    EXPECT_NE(bad.err.find(why), std::string::npos) << bad.err;
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  }

  // Without the plugin, the name is refused in one line.
  const test::CommandResult without =
      lmk(dir, "eval --dataset " + data + " --metric nearest", false);
  EXPECT_EQ(without.exit_code, 2);
  EXPECT_NE(without.err.find("nearest"), std::string::npos) << without.err;
}

}  // namespace
}  // namespace lmk
