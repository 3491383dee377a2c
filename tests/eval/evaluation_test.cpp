// SPDX-License-Identifier: BSD-3-Clause
// The evaluator over a small generated dataset: its table, determinism, resuming from the cache
// after an interruption, its JSON, its report (rendered by headless Chromium when installed), and
// ablations.

#include "lmk/eval/evaluation.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "lmk/datasets/benchmark_dataset.h"
#include "lmk/eval/ablation.h"
#include "lmk/eval/evaluation_report.h"
#include "lmk/eval/evaluation_rows.h"
#include "lmk/eval/evaluation_table.h"
#include "lmk/eval/internal/evaluation_json.h"
#include "lmk/eval/internal/risk_coverage_json.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "tests/eval/simple_scenes_fixture.h"
#include "tests/support/test_support.h"

namespace lmk {
namespace {

// Two simple scenes (a bowl and a cup; three balls) and their three landmarks: 6 pairs.
class EvaluationTest : public test::SimpleScenes {};

void expect_same_results(const Evaluation& a, const Evaluation& b) {
  ASSERT_EQ(a.pairs.size(), b.pairs.size());
  for (std::size_t i = 0; i < a.pairs.size(); ++i) {
    const PairResult &p = a.pairs[i], &q = b.pairs[i];
    EXPECT_EQ(p.scene + "/" + p.landmark, q.scene + "/" + q.landmark);
    ASSERT_EQ(p.found.size(), q.found.size()) << p.scene << " " << p.landmark;
    for (std::size_t k = 0; k < p.found.size(); ++k) {
      EXPECT_TRUE(p.found[k].box.pose.isApprox(q.found[k].box.pose, 1e-12));
      EXPECT_DOUBLE_EQ(p.found[k].error, q.found[k].error);
      const auto violations = [](const ErrorTerms& t) {
        return t.empty_space.value_or(EmptySpaceTerms{}).violations;
      };
      EXPECT_EQ(violations(p.found[k].terms), violations(q.found[k].terms));
    }
  }
}

TEST_F(EvaluationTest, FindsEverythingInSimpleScenesAndTabulatesIt) {
  const Evaluation e = run({});
  ASSERT_EQ(e.pairs.size(), 6u);
  const std::vector<EvaluationRow> rows = evaluation_rows(e);
  ASSERT_EQ(rows.size(), 6u);  // simple and all, assumptions 1-3
  for (const EvaluationRow& row : rows) {
    EXPECT_TRUE(row.setting == "simple" || row.setting == "all");
    // Every instance of a bowl, a cup and three balls, nothing else, within a few millimetres.
    EXPECT_EQ(row.counts.fp, 0u) << row.setting << " " << row.assumption;
    EXPECT_EQ(row.counts.fn, 0u) << row.setting << " " << row.assumption;
    ASSERT_TRUE(row.median_translation_error);
    EXPECT_LT(*row.median_translation_error, 0.01);
    EXPECT_GT(*row.median_seconds, 0.0);
  }
  EXPECT_EQ(rows[0].counts.tp, 5u);  // assumption 1: bowl, cup, three balls
  EXPECT_EQ(rows[2].counts.tp, 3u);  // assumption 3: one best match per in-context pair
  const std::string table = evaluation_table(rows).plain();
  EXPECT_NE(table.find("3 best match"), std::string::npos) << table;
}

// Issue #59: where the dataset gives a landmark no symmetry, the axis its capture found counts
// instead (the ball's: its capture finds it turns freely), and only when asked; a symmetry the
// dataset gives stays the dataset's.
TEST_F(EvaluationTest, TheCapturesSymmetryCountsWhereTheDatasetGivesNone) {
  const Evaluation given = run({});
  for (const PairResult& p : given.pairs) EXPECT_FALSE(p.symmetry_from_capture) << p.landmark;
  EXPECT_EQ(capture_symmetry_note(given), "");

  Dataset without_symmetry = *dataset_;
  for (DatasetLandmark& l : without_symmetry.landmarks) l.symmetry = Symmetry();
  EvaluationSettings settings;
  const Evaluation with_rule = evaluate(dir_->string(), without_symmetry, settings);
  settings.capture_symmetry = false;
  const Evaluation without_rule = evaluate(dir_->string(), without_symmetry, settings);
  bool ball_counted = false;
  for (std::size_t i = 0; i < with_rule.pairs.size(); ++i) {
    const PairResult &p = with_rule.pairs[i], &q = without_rule.pairs[i];
    EXPECT_FALSE(q.symmetry_from_capture);
    EXPECT_FALSE(q.symmetry.axis.has_value());
    if (p.landmark != "ball") continue;
    ASSERT_TRUE(p.symmetry_from_capture) << p.scene;
    ASSERT_TRUE(p.symmetry.axis.has_value());
    // The ball's axis is the scene's up, z in its box frame as the dataset would give it.
    EXPECT_NEAR(std::abs(p.symmetry.axis->z()), 1.0, 0.1);
    ball_counted = true;
  }
  EXPECT_TRUE(ball_counted);
  // The rule only forgives: never fewer true positives, and the note names the landmark.
  const double threshold = *with_rule.settings.find.selection.threshold;
  EXPECT_GE(evaluation_row(with_rule, "all", 1, threshold).counts.tp,
            evaluation_row(without_rule, "all", 1, threshold).counts.tp);
  const std::string note = capture_symmetry_note(with_rule);
  EXPECT_NE(note.find("ball"), std::string::npos) << note;
  EXPECT_EQ(capture_symmetry_note(without_rule), "");
}

TEST_F(EvaluationTest, ResultsDoNotDependOnThreadsOrTheCache) {
  EvaluationSettings one;
  one.threads = 1;
  EvaluationSettings two;
  two.threads = 2;
  test::ScratchDir cache;
  two.cache_dir = cache.path().string();
  const Evaluation a = run(one), b = run(two), c = run(two);
  expect_same_results(a, b);
  expect_same_results(a, c);
  for (const PairResult& p : c.pairs) EXPECT_TRUE(p.from_cache);
}

TEST_F(EvaluationTest, ResumesFromTheCacheAfterAnInterruption) {
  test::ScratchDir cache;
  EvaluationSettings settings;
  settings.threads = 1;
  settings.cache_dir = cache.path().string();
  settings.progress = [](std::size_t done, std::size_t, std::size_t) {
    if (done == 3) throw std::runtime_error("interrupted");
  };
  EXPECT_THROW(run(settings), std::runtime_error);
  settings.progress = nullptr;
  const Evaluation resumed = run(settings);
  std::size_t cached = 0;
  for (const PairResult& p : resumed.pairs) cached += p.from_cache ? 1 : 0;
  EXPECT_EQ(cached, 3u);  // the three done before the interruption, and no other
  EvaluationSettings fresh;
  fresh.threads = 1;
  expect_same_results(resumed, run(fresh));
  // Another search configuration has its own cache entries.
  settings.find.selection.metric = "paper";
  const Evaluation other = run(settings);
  for (const PairResult& p : other.pairs) EXPECT_FALSE(p.from_cache);
}

// A stop request (Ctrl-C in the CLI) lets no further search start: evaluate() throws
// lmk::Interrupted naming what is kept, and the next run resumes from exactly those pairs.
TEST_F(EvaluationTest, StopsOnRequestKeepingWhatIsDone) {
  test::ScratchDir cache;
  EvaluationSettings settings;
  settings.threads = 1;
  settings.cache_dir = cache.path().string();
  std::size_t done = 0;
  settings.progress = [&done](std::size_t d, std::size_t, std::size_t) { done = d; };
  settings.stop_requested = [&done] { return done >= 2; };
  try {
    run(settings);
    ADD_FAILURE() << "the evaluation did not stop";
  } catch (const Interrupted& e) {
    EXPECT_NE(std::string(e.what()).find("interrupted after 2 of 6 pairs; they are cached in"),
              std::string::npos)
        << e.what();
  }
  settings.progress = nullptr;
  settings.stop_requested = nullptr;
  const Evaluation resumed = run(settings);
  std::size_t cached = 0;
  for (const PairResult& p : resumed.pairs) cached += p.from_cache ? 1 : 0;
  EXPECT_EQ(cached, 2u);
  EvaluationSettings fresh;
  fresh.threads = 1;
  expect_same_results(resumed, run(fresh));
}

TEST_F(EvaluationTest, InContextPairsOnlyForAssumptionsTwoAndThree) {
  EvaluationSettings settings;
  settings.in_context_only = true;
  const Evaluation e = run(settings);
  EXPECT_EQ(e.pairs.size(), 3u);  // bowl and cup in one scene, the ball in the other
  for (const EvaluationRow& row : evaluation_rows(e)) EXPECT_NE(row.assumption, 1);
}

// The table split by range adds up to the table: every instance and match lies in some bin, and
// every in-context pair's best match in its instance's.
TEST_F(EvaluationTest, RowsByRangeAddUpToTheWholeTable) {
  EvaluationSettings settings;
  const Evaluation e = run(settings);
  const std::vector<EvaluationRow> whole = evaluation_rows(e),
                                   by_range = evaluation_rows_by_range(e);
  ASSERT_FALSE(by_range.empty());
  for (int assumption : {1, 2, 3}) {
    Counts sum;
    for (const EvaluationRow& row : by_range) {
      if (row.assumption == assumption) sum.add(row.counts);
      EXPECT_NE(row.setting.find(" m"), std::string::npos) << row.setting;
    }
    const auto all = std::find_if(whole.begin(), whole.end(), [&](const EvaluationRow& r) {
      return r.setting == "all" && r.assumption == assumption;
    });
    ASSERT_NE(all, whole.end());
    EXPECT_EQ(sum.tp, all->counts.tp);
    EXPECT_EQ(sum.fp, all->counts.fp);
    EXPECT_EQ(sum.fn, all->counts.fn);
  }
  EXPECT_THROW(evaluation_rows_by_range(e, std::nullopt, 0.0), Error);
}

// Hand-made results: no search, so the JSON and the report can be checked exactly.
Evaluation hand_made() {
  Evaluation e;
  e.settings.find = FindSettings().resolved();  // as evaluate() leaves it
  e.dataset = "hand";
  e.fingerprint = "0123456789abcdef";
  PairResult found;
  found.scene = "s1";
  found.landmark = "cup";
  found.setting = "simple";
  found.in_context = true;
  found.truth = {Eigen::Isometry3d::Identity()};
  found.found = {{Box(Eigen::Isometry3d::Identity(), {0.1, 0.1, 0.1}), 0.002, {}, {}}};
  found.seconds = 0.05;
  PairResult nothing = found;
  nothing.scene = "s2";
  nothing.setting = "cluttered";
  nothing.truth.clear();
  nothing.found.clear();
  e.pairs = {found, nothing};
  return e;
}

// Recall by hidden fraction: each instance in its bin, false matches in none.
TEST(EvaluationByHidden, InstancesCountInTheirBinAndFalseMatchesInNone) {
  Evaluation e = hand_made();
  EXPECT_THROW(evaluation_rows_by_hidden(e), Error);  // nothing recorded
  PairResult& p = e.pairs[0];
  p.truth = {Eigen::Isometry3d::Identity(), pose_from_xyz_rpy({1, 0, 0}, {0, 0, 0})};
  p.truth_hidden = {0.1, 0.5};
  p.found.push_back({Box(pose_from_xyz_rpy({3, 0, 0}, {0, 0, 0}), {0.1, 0.1, 0.1}), 0.003, {}, {}});
  const std::vector<EvaluationRow> rows = evaluation_rows_by_hidden(e);
  // Two bins, assumptions 1 and 2; the pair's best match (right) in its first instance's bin.
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[0].setting, "0-20% hidden");
  EXPECT_EQ(rows[0].counts.tp, 1u);
  EXPECT_EQ(rows[0].counts.fp, 0u);
  EXPECT_EQ(rows[2].setting, "0-20% hidden");
  EXPECT_EQ(rows[2].assumption, 3);
  EXPECT_EQ(rows[2].counts.tp, 1u);
  EXPECT_EQ(rows[2].pairs, 1u);
  EXPECT_EQ(rows[3].setting, "40-60% hidden");
  EXPECT_EQ(rows[3].counts.fn, 1u);
  EXPECT_EQ(rows[3].counts.tp + rows[3].counts.fp, 0u);
  // The JSON carries the record.
  const PairResult back =
      detail::pair_result_from_json(detail::pair_result_to_json(p, 0.006, {}), "pair");
  EXPECT_EQ(back.truth_hidden, p.truth_hidden);
}

// The azimuth to the nearest view is measured about the landmark's up axis, placed by the pose.
TEST(EvaluationByViews, TheAzimuthIsToTheNearestViewAboutTheLandmarksUp) {
  PairResult p;
  p.landmark_up = Eigen::Vector3d::UnitZ();
  p.capture_box = Eigen::Isometry3d::Identity();
  p.sensor_position = Eigen::Vector3d(2, 0, 1);  // the height does not count
  p.view_origins = {Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, 1, 5)};
  EXPECT_NEAR(azimuth_to_nearest_view(p, Eigen::Isometry3d::Identity()), M_PI / 4, 1e-12);
  // The instance turned by 90 degrees about z turns its views with it: (0, 1) comes to (-1, 0) and
  // (1, 1) to (-1, 1), 135 degrees from the sensor's side.
  const Eigen::Isometry3d turned = pose_from_xyz_rpy({0, 0, 0}, {0, 0, M_PI / 2});
  EXPECT_NEAR(azimuth_to_nearest_view(p, turned), 3 * M_PI / 4, 1e-12);
}

// Recall and precision by views: each instance in the bin of its landmark's views and azimuth, a
// false match in the bin of its own pose.
TEST(EvaluationByViews, InstancesAndFalseMatchesCountInTheirViewsAndAzimuth) {
  Evaluation e = hand_made();
  for (PairResult& p : e.pairs) {
    p.landmark_up = Eigen::Vector3d::UnitZ();
    p.sensor_position = Eigen::Vector3d(2, 0, 0);
    p.view_origins = {Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(0, 2, 0)};  // 0 and 90 degrees
  }
  // A false match turned by 65 degrees: its views lie 65 and 155 degrees from the sensor.
  e.pairs[0].found.push_back(
      {Box(pose_from_xyz_rpy({0, 0, 0}, {0, 0, 65.0 * M_PI / 180.0}), {0.1, 0.1, 0.1}),
       0.003,
       {},
       {}});
  const std::vector<EvaluationRow> rows = evaluation_rows_by_views(e);
  std::map<std::pair<std::string, int>, Counts> by;
  for (const EvaluationRow& r : rows) by[{r.setting, r.assumption}] = r.counts;
  const auto counts = [&](const char* bin, int assumption) { return by[{bin, assumption}]; };
  EXPECT_EQ(counts("2 views, 0-15 deg", 2).tp, 1u);
  EXPECT_EQ(counts("2 views, 0-15 deg", 2).fp, 0u);
  EXPECT_EQ(counts("2 views, 60-75 deg", 2).fp, 1u);
  EXPECT_EQ(counts("2 views, 0-15 deg", 3).tp, 1u);  // the best match, right
  EXPECT_THROW(evaluation_rows_by_views(e, {}, 0.0), Error);
}

TEST(EvaluationJson, TheIssueSchemaWithNullForUndefinedPrecision) {
  const Evaluation e = hand_made();
  const nlohmann::json j = detail::evaluation_to_json(e, evaluation_rows(e));
  EXPECT_EQ(j.at("method"), "fast");
  EXPECT_EQ(j.at("metric"), "visibility");
  bool saw_null = false;
  for (const auto& row : j.at("rows")) {
    for (const char* key :
         {"setting", "assumption", "precision", "recall", "tp", "fp", "fn",
          "median_translation_error_m", "median_rotation_error_rad", "median_seconds_per_search"}) {
      EXPECT_TRUE(row.contains(key)) << key;
    }
    if (row.at("setting") == "cluttered") {
      EXPECT_TRUE(row.at("precision").is_null());  // nothing returned: neither 0 nor 1
      EXPECT_TRUE(row.at("recall").is_null());     // nothing to find
      saw_null = true;
    }
    if (row.at("setting") == "simple") {
      EXPECT_EQ(row.at("precision"), 1.0);
    }
  }
  EXPECT_TRUE(saw_null);
  ASSERT_EQ(j.at("pairs").size(), 2u);
  EXPECT_TRUE(j.at("pairs")[0].at("found")[0].at("correct").get<bool>());
  // A pair's JSON reads back as it was.
  const PairResult back = detail::pair_result_from_json(j.at("pairs")[0], "pair");
  EXPECT_EQ(back.found.size(), 1u);
  EXPECT_DOUBLE_EQ(back.found[0].error, 0.002);
}

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(EvaluationReport, WritesJsonMarkdownAndSelfContainedHtml) {
  test::ScratchDir dir;
  write_evaluation_report(dir.file("report"), hand_made());
  const std::filesystem::path out = dir.path() / "report";
  const nlohmann::json j = nlohmann::json::parse(read(out / "report.json"));
  EXPECT_EQ(j.at("threshold_curves").size(), 3u);  // simple, cluttered, all
  EXPECT_NE(read(out / "report.md").find("| setting |"), std::string::npos);
  EXPECT_NE(read(out / "report.md").find("## By range"), std::string::npos);
  EXPECT_NE(read(out / "report.html").find("<h2>By range</h2>"), std::string::npos);
  // Every section of the report is in both files, and the JSON has what lmk eval --json has.
  const std::string markdown = read(out / "report.md");
  const std::string html = read(out / "report.html");
  for (const std::string section : {"Precision and recall", "By range", "Confidence", "Pairs"}) {
    EXPECT_NE(markdown.find("## " + section + "\n"), std::string::npos) << section;
    EXPECT_NE(html.find("<h2>" + section + "</h2>"), std::string::npos) << section;
  }
  EXPECT_NE(markdown.find("| at a cut |"), std::string::npos);  // the risk-coverage table
  EXPECT_EQ(j.at("confidence"), detail::confidence_evaluation_to_json(hand_made()));
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_EQ(occurrences(html, "<svg"), 2u);  // the threshold curves and the times
  for (const std::string tag : {"table", "svg", "figure", "tr", "td", "th", "body", "html"}) {
    EXPECT_EQ(occurrences(html, "<" + tag + ">") + occurrences(html, "<" + tag + " "),
              occurrences(html, "</" + tag + ">"))
        << "unbalanced <" << tag << ">";
  }
  EXPECT_EQ(html.find("http://"), html.find("http://www.w3.org/2000/svg"));  // nothing external
}

// Headless Chromium, for the tests that render the report in a real browser.
const char* const kNoChromium = "chromium is not installed (scripts/install-deps.sh installs it)";
bool has_chromium() { return std::system("command -v chromium >/dev/null 2>&1") == 0; }
// Its command line, with a profile of its own in `dir`.
std::string chromium(const test::ScratchDir& dir) {
  return "chromium --headless --no-sandbox --disable-gpu --disable-dev-shm-usage --user-data-dir=" +
         dir.file("profile") + " ";
}
// The DOM Chromium builds from the HTML file `page` (empty if it fails).
std::string rendered_dom(const test::ScratchDir& dir, const std::string& page) {
  const std::string dom = dir.file("dom.html");
  if (std::system(
          (chromium(dir) + "--dump-dom file://" + page + " > " + dom + " 2>/dev/null").c_str()) !=
      0)
    return "";
  return read(dom);
}

// The report renders in a real browser: headless Chromium parses it, and the DOM it builds holds
// the tables and the plots.
TEST(EvaluationReport, RendersInHeadlessChromium) {
  if (!has_chromium()) GTEST_SKIP() << kNoChromium;
  test::ScratchDir dir;
  write_evaluation_report(dir.file("report"), hand_made());
  const std::string html = dir.file("report/report.html"), png = dir.file("shot.png");
  const std::string flags = chromium(dir);
  const std::string rendered = rendered_dom(dir, html);
  EXPECT_EQ(occurrences(rendered, "<svg"), 2u);
  EXPECT_GE(occurrences(rendered, "<table"), 2u);
  EXPECT_NE(rendered.find("lmk evaluation: hand"), std::string::npos);
  ASSERT_EQ(std::system((flags + "--window-size=1000,1400 --screenshot=" + png + " file://" + html +
                         " >/dev/null 2>&1")
                            .c_str()),
            0);
  EXPECT_GT(std::filesystem::file_size(png), 10000u);  // a page with content, not a blank one
}

// Failure pictures: a pair whose match is dropped (a missed instance) and one with a match moved
// 30 cm off (a false match and a miss) are pictured on their scenes' depth images, with the
// boxes drawn, and the page renders in headless Chromium with its embedded images.
TEST_F(EvaluationTest, ReportPicturesEachFailureAndRendersInHeadlessChromium) {
  Evaluation e = run({});
  ASSERT_GE(e.pairs.size(), 2u);
  ASSERT_FALSE(e.pairs[0].found.empty());
  ASSERT_FALSE(e.pairs[1].found.empty());
  e.pairs[0].found.clear();
  e.pairs[1].found.resize(1);
  e.pairs[1].found[0].box.pose.translation().x() += 0.3;
  test::ScratchDir out;
  write_evaluation_report(out.file("report"), e, dir_->string());
  const nlohmann::json j = nlohmann::json::parse(read(out.path() / "report/report.json"));
  const nlohmann::json& failures = j.at("failures");
  EXPECT_EQ(failures.at("pairs_with_failures"), 2);
  ASSERT_EQ(failures.at("pictured").size(), 2u);
  EXPECT_EQ(failures["pictured"][0].at("missed"), 1);
  EXPECT_EQ(failures["pictured"][1].at("false_matches"), 1);
  EXPECT_NE(failures["pictured"][1].at("caption").get<std::string>().find("false match at"),
            std::string::npos);
  const std::string html = read(out.path() / "report/report.html");
  const std::size_t from = html.find("<h2>Failures</h2>"), to = html.find("<h2>Pairs</h2>");
  ASSERT_LT(from, to);
  const std::string section = html.substr(from, to - from);
  EXPECT_EQ(occurrences(section, "href=\"data:image/png;base64,"), 2u);
  EXPECT_EQ(occurrences(section, "stroke=\"#ee6677\""), 12u);  // the false match's 12 edges
  EXPECT_NE(read(out.path() / "report/report.md").find("## Failures"), std::string::npos);

  if (!has_chromium()) GTEST_SKIP() << kNoChromium;
  const std::string rendered = rendered_dom(out, out.file("report/report.html"));
  EXPECT_EQ(occurrences(rendered, "<figcaption>"), 2u);
  EXPECT_EQ(occurrences(rendered, "<image "), 2u);
  EXPECT_GE(occurrences(rendered, "<line "), 24u);
}

TEST(Ablation, AxesParseWithClearErrors) {
  const AblationAxis axis = parse_ablation_axis("metric=paper,vdb");
  EXPECT_EQ(axis.key, "metric");
  EXPECT_EQ(axis.values, (std::vector<std::string>{"paper", "vdb"}));
  EXPECT_THROW(parse_ablation_axis("metric"), Error);
  EXPECT_THROW(parse_ablation_axis("metric=paper,,vdb"), Error);
  EXPECT_THROW(parse_ablation_axis("metric=paper,paper"), Error);
  EXPECT_THROW(parse_ablation_axis("metric=nope"), Error);
  EXPECT_THROW(parse_ablation_axis("threshold=-1"), Error);
  EXPECT_THROW(parse_ablation_axis("threads=1,2"), Error);          // how to run, not what is found
  const AblationAxis tilt = parse_ablation_axis("max-tilt=30,45");  // any search setting
  FindSettings s;
  apply_ablation_setting(s, tilt.key, tilt.values[1]);
  EXPECT_NEAR(s.fast.max_tilt, M_PI / 4.0, 1e-12);
  try {
    parse_ablation_axis("colour=red");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("max-seeds"), std::string::npos) << e.what();
  }
}

TEST_F(EvaluationTest, AblationRunsTheGridAndResumes) {
  test::ScratchDir cache;
  EvaluationSettings base;
  base.cache_dir = cache.path().string();
  base.in_context_only = true;
  const std::vector<AblationAxis> axes = {parse_ablation_axis("metric=vdb,visibility"),
                                          parse_ablation_axis("threshold=0.004,0.005")};
  const auto first = run_ablation(dir_->string(), *dataset_, base, axes);
  ASSERT_EQ(first.size(), 4u);
  EXPECT_EQ(first[1].label(), "metric=vdb threshold=0.005");
  // Thresholds at or below the metric's default share one search, so half the variants, and all of
  // a second run, come from the cache.
  std::size_t cached = 0;
  for (const auto& v : first) {
    for (const PairResult& p : v.evaluation.pairs) cached += p.from_cache ? 1 : 0;
  }
  EXPECT_EQ(cached, 6u);
  const auto second = run_ablation(dir_->string(), *dataset_, base, axes);
  for (std::size_t i = 0; i < first.size(); ++i) {
    for (const PairResult& p : second[i].evaluation.pairs) EXPECT_TRUE(p.from_cache);
    expect_same_results(first[i].evaluation, second[i].evaluation);
  }
  const TextTable table = ablation_table(second);
  EXPECT_EQ(table.rows.size(), 4u);
  EXPECT_EQ(table.header[0], "metric");
  EXPECT_EQ(table.header[1], "threshold");
}

}  // namespace
}  // namespace lmk

namespace lmk {
namespace {

// A shard is a function of the pair's names alone (adding scenes moves no other pair), and the
// pairs spread evenly over the shards.
TEST(PairShard, DependsOnTheNamesAloneAndSpreadsThePairs) {
  std::array<int, 4> per_shard{};
  for (int s = 0; s < 40; ++s) {
    for (int l = 0; l < 25; ++l) {
      const std::string scene = "cluttered/scene-" + std::to_string(s);
      const std::string landmark = "landmark_" + std::to_string(l);
      const int shard = pair_shard(scene, landmark, 4);
      ASSERT_GE(shard, 1);
      ASSERT_LE(shard, 4);
      EXPECT_EQ(pair_shard(scene, landmark, 4), shard);
      ++per_shard[static_cast<std::size_t>(shard - 1)];
    }
  }
  for (int n : per_shard) {
    EXPECT_GT(n, 200);  // 250 each if perfectly even
    EXPECT_LT(n, 300);
  }
  EXPECT_EQ(pair_shard("a", "b", 1), 1);
  EXPECT_NE(pair_shard("ab", "c", 1 << 20), pair_shard("a", "bc", 1 << 20));
}

// Generation shards: paper-x100's 1,700 scene names spread evenly over 8 shards, and a scene's
// shard is its name's alone (a dataset that grows leaves every scene where it was).
TEST(SceneShard, SpreadsAPresetsScenesEvenlyByName) {
  std::array<int, 8> per_shard{};
  for (const std::string& type : scene_types()) {
    for (std::uint64_t seed = 1; seed <= 100; ++seed) {
      const std::string name = benchmark_scene_name(type, seed, false);
      const int shard = scene_shard(name, 8);
      ASSERT_GE(shard, 1);
      ASSERT_LE(shard, 8);
      EXPECT_EQ(scene_shard(name, 8), shard);
      ++per_shard[static_cast<std::size_t>(shard - 1)];
    }
  }
  for (int n : per_shard) {
    EXPECT_GT(n, 170);  // 212.5 each if perfectly even
    EXPECT_LT(n, 255);
  }
  EXPECT_EQ(scene_shard("anything", 1), 1);
}

TEST(PairShard, ParsesKOfN) {
  EXPECT_EQ(parse_shard("2/8").index, 2);
  EXPECT_EQ(parse_shard("2/8").count, 8);
  EXPECT_EQ(parse_shard("1/1").count, 1);
  for (const char* bad : {"0/3", "4/3", "3", "1/0", "a/b", "1/3x", "-1/3", ""}) {
    EXPECT_NE(test::error_of([&] { parse_shard(bad); }).find("must be K/N"), std::string::npos)
        << bad;
  }
}

}  // namespace
}  // namespace lmk
