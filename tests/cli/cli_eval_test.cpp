// SPDX-License-Identifier: BSD-3-Clause
// The lmk command line end to end, its evaluation commands: gen, eval, ablate, shards, Slurm.

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

TEST_F(Cli, GenPresetEvalAndAblateOnASmallDataset) {
  const CommandResult gen =
      lmk("gen --preset paper --types simple/three_balls,simple/bowl_and_cup " + path("data"));
  ASSERT_EQ(gen.exit_code, 0) << gen.err;
  EXPECT_NE(gen.out.find("3 landmarks, 2 scenes, 3 in-context pairs"), std::string::npos)
      << gen.out;

  const CommandResult eval = lmk("eval --dataset " + path("data") + " --cache " + path("cache") +
                                 " --json " + path("eval.json") + " --report " + path("report"));
  ASSERT_EQ(eval.exit_code, 0) << eval.err;
  EXPECT_NE(eval.out.find("3 best match"), std::string::npos) << eval.out;
  // Not a terminal: no progress bar, one summary line.
  EXPECT_NE(eval.err.find("eval: 6 pairs (6 searched, 0 from the cache)"), std::string::npos)
      << eval.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(dir_.file("eval.json")));
  EXPECT_EQ(j.at("method"), "fast");
  EXPECT_EQ(j.at("rows").size(), 6u);
  EXPECT_EQ(j.at("pairs").size(), 6u);
  for (const char* f : {"report.html", "report.md", "report.json"})
    EXPECT_TRUE(std::filesystem::exists(dir_.path() / "report" / f)) << f;
  // A second run resumes from the cache.
  const CommandResult again = lmk("eval --dataset " + path("data") + " --cache " + path("cache"));
  EXPECT_NE(again.err.find("(0 searched, 6 from the cache)"), std::string::npos) << again.err;

  const CommandResult ablate =
      lmk("ablate --dataset " + path("data") + " --cache " + path("cache") +
          " --pairs in-context --vary metric=paper,vdb " + "--out " + path("ablation"));
  ASSERT_EQ(ablate.exit_code, 0) << ablate.err;
  EXPECT_NE(ablate.out.find("metric"), std::string::npos);
  EXPECT_NE(ablate.out.find("vdb"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir_.path() / "ablation" / "ablation.json"));
  EXPECT_TRUE(std::filesystem::exists(dir_.path() / "ablation" / "ablation.md"));
}

// lmk eval --shard K/N on three "machines", then --merge: the JSON of the single-machine run, byte
// for byte; a pair lost from the cache is named by the merge and recomputed alone (issue #20).
TEST_F(Cli, ShardedEvaluationMergesToTheSingleMachineRun) {
  ASSERT_EQ(lmk("gen --preset paper --types simple/three_balls,simple/bowl_and_cup,"
                "cluttered/spray_with_clutter " +
                path("data"))
                .exit_code,
            0);
  const std::string data = " --dataset " + path("data");
  const CommandResult single =
      lmk("eval" + data + " --cache " + path("one") + " --json " + path("single.json"));
  ASSERT_EQ(single.exit_code, 0) << single.err;
  const std::regex counted(R"(: (\d+) pairs \((\d+) searched, (\d+) from the cache\))");
  const auto counts = [&counted](const std::string& err) {
    std::smatch m;
    return std::regex_search(err, m, counted)
               ? std::array<int, 3>{std::stoi(m[1]), std::stoi(m[2]), std::stoi(m[3])}
               : std::array<int, 3>{-1, -1, -1};
  };
  const int total = counts(single.err)[0];
  ASSERT_GT(total, 3);
  const std::string cluster = data + " --cache " + path("cluster");
  int sharded = 0;
  for (int k = 1; k <= 3; ++k) {
    const CommandResult shard = lmk("eval" + cluster + " --shard " + std::to_string(k) + "/3");
    ASSERT_EQ(shard.exit_code, 0) << shard.err;
    sharded += counts(shard.err)[1];
    EXPECT_NE(shard.out.find("lmk eval --merge"), std::string::npos) << shard.out;
  }
  EXPECT_EQ(sharded, total);  // every pair in exactly one shard
  const CommandResult merged = lmk("eval" + cluster + " --merge --json " + path("merged.json"));
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_EQ(counts(merged.err), (std::array<int, 3>{total, 0, total}));
  EXPECT_EQ(slurp(dir_.file("merged.json")), slurp(dir_.file("single.json")));
  EXPECT_EQ(merged.out, single.out);  // the table too: its times only come with --timings
  EXPECT_EQ(single.out.find("s/search"), std::string::npos) << single.out;
  EXPECT_NE(lmk("eval" + cluster + " --merge --timings").out.find("s/search"), std::string::npos);

  // A pair lost (a shard that crashed before writing it): the merge names it and refuses.
  std::filesystem::path lost;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir_.file("cluster"))) {
    if (e.path().parent_path().parent_path().filename() == "evaluations") lost = e.path();
  }
  ASSERT_FALSE(lost.empty());
  const nlohmann::json entry = nlohmann::json::parse(slurp(lost.string()));
  std::filesystem::remove(lost);
  expect_bad_input("eval" + cluster + " --merge",
                   "merge: 1 of " + std::to_string(total) + " pairs are not in the cache (" +
                       entry.at("scene").get<std::string>() + " x " +
                       entry.at("landmark").get<std::string>() + ")");
  // Rerunning every shard computes that pair alone.
  int searched = 0;
  for (int k = 1; k <= 3; ++k) {
    searched += counts(lmk("eval" + cluster + " --shard " + std::to_string(k) + "/3").err)[1];
  }
  EXPECT_EQ(searched, 1);
  ASSERT_EQ(lmk("eval" + cluster + " --merge --json " + path("again.json")).exit_code, 0);
  EXPECT_EQ(slurp(dir_.file("again.json")), slurp(dir_.file("single.json")));

  expect_bad_input("eval" + data + " --shard 4/3", "shard '4/3'");
  expect_bad_input("eval" + data + " --shard 1-3", "shard '1-3'");
  expect_bad_input("eval" + data + " --no-cache --shard 1/3", "--no-cache");
  expect_bad_input("eval" + data + " --no-cache --merge", "--no-cache");
}

// lmk slurm eval writes the job chain (tests/cluster/slurm_test.sh runs it on a real Slurm): a
// generation array and its merge for a preset, an evaluation array whose tasks run the shards into
// one cache, a merge after it, and submit.sh chaining them with afterok.
TEST_F(Cli, SlurmEvalWritesTheJobChainAndChecksTheEvalArguments) {
  const CommandResult r =
      lmk("slurm eval --dir " + path("job") + " --tasks 5 --cpus-per-task 3 --time 01:00:00" +
          " --partition batch --sbatch=--qos=short -- --preset paper-x10 --seeds 2 --hard" +
          " --metric sensor --json " + path("out.json") + " --timings");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string gen = slurp(dir_.file("job/gen.sbatch"));
  EXPECT_NE(gen.find("#SBATCH --array=1-5\n"), std::string::npos) << gen;
  EXPECT_NE(gen.find(" gen --preset paper-x10 " + dir_.file("job/dataset") +
                     " --seeds 2 --hard --shard \"${SLURM_ARRAY_TASK_ID}/5\""),
            std::string::npos)
      << gen;
  EXPECT_NE(slurp(dir_.file("job/gen-merge.sbatch")).find(" --merge\n"), std::string::npos);
  const std::string eval = slurp(dir_.file("job/eval.sbatch"));
  for (const std::string& line :
       std::vector<std::string>{"#SBATCH --cpus-per-task=3\n", "#SBATCH --time=01:00:00\n",
                                "#SBATCH --partition=batch\n", "#SBATCH --qos=short\n",
                                "#SBATCH --output=" + dir_.file("job/logs/eval-%A_%a.out") + "\n",
                                " eval --dataset " + dir_.file("job/dataset") +
                                    " --metric sensor --cache " + dir_.file("job/cache") +
                                    " --threads \"${SLURM_CPUS_PER_TASK:-3}\" --shard "
                                    "\"${SLURM_ARRAY_TASK_ID}/5\"\n"}) {
    EXPECT_NE(eval.find(line), std::string::npos) << line << " not in\n" << eval;
  }
  EXPECT_EQ(eval.find("--json"), std::string::npos);  // the merge's alone
  const std::string merge = slurp(dir_.file("job/merge.sbatch"));
  EXPECT_NE(merge.find(" --merge --json " + dir_.file("out.json") + " --timings --report " +
                       dir_.file("job/report")),
            std::string::npos)
      << merge;
  const std::string submit = slurp(dir_.file("job/submit.sh"));
  EXPECT_NE(submit.find("--dependency=afterok:\"${gen%%;*}\" gen-merge.sbatch"), std::string::npos);
  EXPECT_NE(submit.find("--array=\"$tasks\" eval.sbatch"), std::string::npos);
  EXPECT_NE(submit.find("--dependency=afterok:\"${evaluation%%;*}\" merge.sbatch"),
            std::string::npos);
  EXPECT_NE(r.out.find("submit with: bash " + dir_.file("job/submit.sh")), std::string::npos);

  expect_bad_input("slurm eval --dir " + path("j") + " -- --shard 1/2", "--shard is the job's");
  expect_bad_input("slurm eval --dir " + path("j") + " -- --threads 4", "--threads is the job's");
  expect_bad_input("slurm eval --dir " + path("j") + " -- --metric nope", "lmk eval");
  expect_bad_input("slurm eval --dir " + path("j") + " -- --dataset " + path("none"),
                   "dataset.json does not exist");
  expect_bad_input("slurm eval --tasks 0", "--tasks");
  expect_bad_input("eval --dataset " + path("j") + " --types simple/three_balls", "--types");
  expect_bad_input("slurm", "A subcommand is required");
}

// lmk slurm eval writes no shell line from its options (issue #34, finding 4). Each option that
// reaches an "#SBATCH" line is refused, in one line, with a newline, a $( ), a quote or a backtick
// in it (--sbatch with a newline: its other values are comments to bash, passed to sbatch as
// given). A job directory and --sbatch values holding them are written inert: every script, run by
// bash with a fake sbatch and a fake lmk, touches nothing.
TEST_F(Cli, SlurmEvalWritesNoShellLineFromItsOptions) {
  namespace fs = std::filesystem;
  const auto quoted = [](const std::string& text) {
    std::string out = "'";
    for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
  };
  const std::vector<std::string> payloads = {"p\nid > pwned", "p$(touch pwned)", "p'q",
                                             "p`touch pwned`"};
  for (const char* option :
       {"--time", "--merge-time", "--partition", "--account", "--mem-per-cpu"}) {
    for (const std::string& payload : payloads) {
      expect_bad_input("slurm eval --dir " + path("j") + " " + option + " " + quoted(payload) +
                           " -- --preset paper",
                       std::string(option) + " '");
    }
  }
  expect_bad_input(
      "slurm eval --dir " + path("j") + " --sbatch=" + quoted("--qos=a\nid") + " -- --preset paper",
      "control character");
  expect_bad_input("slurm eval --dir " + path("j") + " --time 1:2:3:4 -- --preset paper",
                   "--time '1:2:3:4' is not a Slurm time");
  expect_bad_input("slurm eval --dir " + path("j") + " --sbatch=qos -- --preset paper",
                   "is not an sbatch option");
  ASSERT_EQ(lmk("slurm eval --dir " + path("ok") +
                " --time 1-02:30 --merge-time 45 --partition a,b --account x.y --mem-per-cpu 2G"
                " -- --preset paper")
                .exit_code,
            0);

  const fs::path bin = dir_.path() / "bin";
  fs::create_directories(bin);
  test::write_text((bin / "sbatch").string(), "#!/bin/sh\necho 42\n");
  test::write_text((bin / "lmk").string(), "#!/bin/sh\nexit 0\n");
  for (const char* tool : {"sbatch", "lmk"})
    fs::permissions(bin / tool, fs::perms::owner_all, fs::perm_options::add);
  const fs::path job = dir_.path() / "d$(touch pwned)`touch pwned`'q";
  const CommandResult written =
      lmk("slurm eval --dir " + quoted(job.string()) + " --lmk " + quoted((bin / "lmk").string()) +
          " --sbatch=" + quoted("--comment=$(touch pwned)`touch pwned`'q") +
          " -- --preset paper --json " + quoted((job / "e$(touch pwned).json").string()));
  ASSERT_EQ(written.exit_code, 0) << written.err;
  for (const char* script :
       {"submit.sh", "gen.sbatch", "gen-merge.sbatch", "eval.sbatch", "merge.sbatch"}) {
    const std::string command = "cd " + quoted(job.string()) + " && PATH=" + quoted(bin.string()) +
                                ":\"$PATH\" SLURM_ARRAY_TASK_ID=1 bash " + script +
                                " > /dev/null 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << script;
  }
  for (const auto& entry : fs::recursive_directory_iterator(dir_.path()))
    EXPECT_NE(entry.path().filename(), "pwned") << entry.path();
}

// lmk gen --shard K/N renders a stable share of the scenes; --merge writes the dataset.json of
// the one-machine generation, or names the scenes no shard has rendered yet (issue #20).
TEST_F(Cli, ShardedGenerationMergesToTheOneMachineDataset) {
  const std::string preset =
      "gen --preset paper --seeds 2 --types simple/three_balls,"
      "cluttered/spray_with_clutter,unconventional/drawer ";
  ASSERT_EQ(lmk(preset + path("one")).exit_code, 0);
  const std::regex counted(
      R"((\d+) of the dataset's scenes are this shard's: (\d+) rendered, (\d+))");
  const auto counts = [&counted](const std::string& out) {
    std::smatch m;
    return std::regex_search(out, m, counted)
               ? std::array<int, 3>{std::stoi(m[1]), std::stoi(m[2]), std::stoi(m[3])}
               : std::array<int, 3>{-1, -1, -1};
  };
  int rendered = 0;
  for (int k = 1; k <= 3; ++k) {
    const CommandResult shard =
        lmk(preset + path("sharded") + " --shard " + std::to_string(k) + "/3");
    ASSERT_EQ(shard.exit_code, 0) << shard.err;
    const auto c = counts(shard.out);
    EXPECT_EQ(c[1], c[0]) << shard.out;
    rendered += c[1];
    if (k == 2) {
      // Before the last shard has run, the merge names what is missing and writes nothing.
      const CommandResult early = lmk(preset + path("sharded") + " --merge");
      EXPECT_EQ(early.exit_code, 2);
      EXPECT_NE(early.err.find("scenes are not rendered yet ("), std::string::npos) << early.err;
      EXPECT_FALSE(std::filesystem::exists(dir_.file("sharded/dataset.json")));
    }
  }
  EXPECT_EQ(rendered, 6);  // every scene in exactly one shard
  // A rerun of a shard renders nothing again.
  EXPECT_EQ(counts(lmk(preset + path("sharded") + " --shard 2/3").out)[1], 0);
  const CommandResult merged = lmk(preset + path("sharded") + " --merge");
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_EQ(slurp(dir_.file("sharded/dataset.json")), slurp(dir_.file("one/dataset.json")));
  for (const auto& e : std::filesystem::directory_iterator(dir_.file("one/scenes"))) {
    EXPECT_EQ(slurp(dir_.file("sharded/scenes/" + e.path().filename().string())),
              slurp(e.path().string()))
        << e.path();
  }
  // Evaluated, the two datasets are one: the same fingerprint, so the same cached results.
  const CommandResult a = lmk("eval --dataset " + path("one") + " --cache " + path("cache"));
  const CommandResult b = lmk("eval --dataset " + path("sharded") + " --cache " + path("cache"));
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_NE(b.err.find("(0 searched,"), std::string::npos) << b.err;
  EXPECT_EQ(a.out, b.out);
  expect_bad_input(preset + path("x") + " --shard 0/3", "shard '0/3'");
  expect_bad_input("gen " + path("y.pcd") + " --shard 1/2", "need --preset");
}

// The same inputs and settings give byte-identical JSON: across thread counts, across runs, and
// for eval across a cold cache and a resumed one (issue #17). Wall-clock times, which differ by
// nature, are left out unless --timings asks for them.
// A landmark of one view in the format lmk wrote before landmarks of several views existed
// (fixtures/cup_v2.lmk: `lmk capture` of the generated tabletop's cup, --leaf 0.01, by build
// 4cba8fa) reads as version 2 and searches as it did then: the matches and the rejected
// candidates of fixtures/cup_v2_find.json, `lmk find --rejected --json` of that build, to the bit
// (written again by issue #63's coarse stop, which moved its poses by under a micrometre: the same
// matches, rejected candidates, seeds, votes and ICP steps).
TEST_F(Cli, AOneViewLandmarkOfTheVersion2FormatSearchesAsItDid) {
  const std::string fixture = std::string(LMK_CLI_FIXTURES) + "/cup_v2.lmk";
  ASSERT_EQ(lmk("gen " + path("tab.pcd")).exit_code, 0);
  const CommandResult show = lmk("landmark show '" + fixture + "'");
  ASSERT_EQ(show.exit_code, 0) << show.err;
  EXPECT_NE(show.out.find("format         lmk 2"), std::string::npos) << show.out;
  EXPECT_NE(show.out.find("views          1"), std::string::npos) << show.out;
  const CommandResult found =
      lmk("find " + path("tab.pcd") + " '" + fixture + "' --rejected --json -");
  ASSERT_EQ(found.exit_code, 0) << found.err;
  auto j = nlohmann::json::parse(found.out);
  const auto expected =
      nlohmann::json::parse(slurp(std::string(LMK_CLI_FIXTURES) + "/cup_v2_find.json"));
  // The fixture predates the confidence (issue #45): every match now has one, and the rest of it
  // is what the search found then.
  for (auto& m : j["matches"]) {
    EXPECT_TRUE(m.contains("confidence")) << m.dump();
    m.erase("confidence");
  }
  EXPECT_EQ(j["matches"].dump(), expected["matches"].dump());
  EXPECT_EQ(j["rejected"].dump(), expected["rejected"].dump());
}

// Several frames of one scene are fused before the search (docs/cli.md, "Several frames"): the
// tabletop twice finds the cup where the frame alone does, moved with the frames by --poses; a
// poses file that does not match the frames, an unorganised frame, or no landmark is refused in
// one line.
TEST_F(Cli, SeveralFramesOfOneSceneAreFusedBeforeTheSearch) {
  const std::string cup = "'" + std::string(LMK_CLI_FIXTURES) + "/cup_v2.lmk'";
  ASSERT_EQ(lmk("gen " + path("tab.pcd")).exit_code, 0);
  const auto first_match = [&](const std::string& args) {
    const CommandResult r = lmk("find " + args + " --json -");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_FALSE(j["matches"].empty()) << r.out;
    const auto& p = j["matches"][0]["position"];
    return Eigen::Vector3d(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
  };
  const Eigen::Vector3d alone = first_match(path("tab.pcd") + " " + cup);
  const Eigen::Vector3d fused = first_match(path("tab.pcd") + " " + path("tab.pcd") + " " + cup);
  EXPECT_LT((fused - alone).norm(), 0.01);
  std::ofstream(dir_.file("poses.txt")) << "# x y z qx qy qz qw\n1 2 0 0 0 0 1\n1 2 0 0 0 0 1\n";
  const Eigen::Vector3d moved = first_match(path("tab.pcd") + " " + path("tab.pcd") + " " + cup +
                                            " --poses " + path("poses.txt"));
  EXPECT_LT((moved - alone - Eigen::Vector3d(1, 2, 0)).norm(), 0.01);

  std::ofstream(dir_.file("one.txt")) << "0 0 0 0 0 0 1\n";
  expect_bad_input(
      "find " + path("tab.pcd") + " " + path("tab.pcd") + " " + cup + " --poses " + path("one.txt"),
      "1 poses for 2 frames");
  ASSERT_EQ(lmk("convert " + path("tab.pcd") + " " + path("flat.xyz")).exit_code, 0);
  expect_bad_input("find " + path("tab.pcd") + " " + path("flat.xyz") + " " + cup,
                   "frame 2: an unorganised cloud");
  expect_bad_input("find " + cup, "At least 2 required");
  // Issue #61, finding 3: the frames are counted before any is read (31 names of files that do not
  // exist are refused for their number, not for the first missing file).
  std::string many;
  for (int i = 0; i < 31; ++i) many += path("absent" + std::to_string(i) + ".pcd") + " ";
  expect_bad_input("find " + many + cup, "31 frames: lmk fuses at most 30 frames of one scene");
}

TEST_F(Cli, JsonOutputIsByteIdenticalAcrossThreadsRunsAndTheCache) {
  ASSERT_EQ(lmk("gen --preset paper --types simple/three_balls,cluttered/spray_with_clutter " +
                path("data"))
                .exit_code,
            0);
  // A cold cache first, then resumed from it, then no cache at all, on 1, 2 and 8 threads.
  const std::string cache = " --cache " + path("cache");
  const std::vector<std::string> runs = {cache + " --threads 1", cache + " --threads 2",
                                         cache + " --threads 8", " --no-cache --threads 8",
                                         " --no-cache --threads 2"};
  std::string first;
  for (std::size_t run = 0; run < runs.size(); ++run) {
    SCOPED_TRACE("eval" + runs[run]);
    const std::string out = "eval-" + std::to_string(run) + ".json";
    const CommandResult r =
        lmk("eval --dataset " + path("data") + runs[run] + " --json " + path(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string json = slurp(dir_.file(out));
    ASSERT_FALSE(json.empty());
    if (first.empty()) {
      first = json;
    } else {
      EXPECT_EQ(json, first);
    }
  }
  EXPECT_EQ(first.find("seconds"), std::string::npos);

  // find on one of the scenes, with a landmark from the dataset.
  const nlohmann::json dataset = nlohmann::json::parse(slurp(dir_.file("data/dataset.json")));
  const std::string scene = path("data/" + dataset["scenes"][1]["file"].get<std::string>());
  const std::string landmark = path("data/" + dataset["landmarks"][0]["file"].get<std::string>());
  std::string found;
  for (const std::string threads : {"1", "2", "8", "8"}) {
    SCOPED_TRACE("find --threads " + threads);
    const CommandResult r =
        lmk("find " + scene + " " + landmark + " --threads " + threads + " --json -");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    if (found.empty()) {
      found = r.out;
    } else {
      EXPECT_EQ(r.out, found);
    }
  }
}

// Ctrl-C during eval: the searches under way finish and are cached, the run says what it kept
// and exits 130; the same command then resumes, and its results are those of an uninterrupted run.
TEST_F(Cli, EvalStopsOnSigintAndResumes) {
  ASSERT_EQ(lmk("gen --preset paper --types simple/three_balls,cluttered/spray_with_clutter " +
                path("data"))
                .exit_code,
            0);
  const std::string eval = std::string("'") + LMK_BINARY + "' eval --dataset " + path("data") +
                           " --threads 1 --cache " + path("cache");
  // Wait for the first finished pair in the cache, then interrupt.
  test::write_text(dir_.file("stop.sh"),
                   eval + " --json " + path("stopped.json") + " >" + path("out") + " 2>" +
                       path("err") +
                       " &\npid=$!\nfor i in $(seq 1 1200); do\n"
                       "  [ -n \"$(find " +
                       path("cache") +
                       " -name '[0-9a-f]*.json' 2>/dev/null)\" ] && break\n"
                       "  sleep 0.05\ndone\nkill -INT $pid\nwait $pid\necho $? >" +
                       path("rc") + "\n");
  ASSERT_EQ(std::system(("sh " + path("stop.sh")).c_str()), 0);
  EXPECT_EQ(slurp(dir_.file("rc")), "130\n") << slurp(dir_.file("err"));
  const std::string err = slurp(dir_.file("err"));
  EXPECT_NE(err.find("lmk: interrupted after "), std::string::npos) << err;
  EXPECT_NE(err.find(": the same command resumes from them"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(dir_.file("stopped.json")));  // no partial results

  const CommandResult resumed = lmk("eval --dataset " + path("data") + " --threads 1 --cache " +
                                    path("cache") + " --json " + path("resumed.json"));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  const std::regex summary(R"(\(([0-9]+) searched, ([0-9]+) from the cache\))");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(resumed.err, m, summary)) << resumed.err;
  EXPECT_GE(std::stoi(m[2]), 1);
  EXPECT_GE(std::stoi(m[1]), 1);  // it was stopped before the end
  ASSERT_EQ(
      lmk("eval --dataset " + path("data") + " --threads 1 --no-cache --json " + path("whole.json"))
          .exit_code,
      0);
  EXPECT_EQ(slurp(dir_.file("resumed.json")), slurp(dir_.file("whole.json")));
}

TEST_F(Cli, EvaluationErrorsAreOneLine) {
  expect_bad_input("gen --preset papers " + path("x"), "unknown preset 'papers'");
  expect_bad_input("gen --types simple/three_balls " + path("x.pcd"), "need --preset");
  expect_bad_input("eval --dataset " + path("nowhere"), "dataset.json");
  expect_bad_input("eval --preset nope", "unknown preset 'nope'");
  expect_bad_input("eval --preset paper --first-seed 0", "--first-seed");
  expect_bad_input("ablate --vary colour=red", "unknown setting 'colour'");
  expect_bad_input("ablate --vary metric=paper,paper", "given twice");
  expect_bad_input("bench --repeats 0", "--repeats");
  expect_bad_input("bench --scenes 3", "--scenes requires --motion");
  expect_bad_input("bench --motion --scenes 0", "--scenes");
  expect_bad_input("bench --motion --frames 2", "do not apply");
}

// lmk bench --motion (issue #60): every scene's line checked, the plans around the box counted,
// and the figures in the JSON.
TEST_F(Cli, BenchMotionTimesLinesAndPlans) {
  const CommandResult r = lmk("bench --motion --scenes 3 --json " + path("motion.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("check a line"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(slurp(dir_.file("motion.json")));
  EXPECT_EQ(j["scenes"].get<int>(), 3);
  EXPECT_GT(j["line"]["median_ms"].get<double>(), 0.0);
  EXPECT_LE(j["plan"]["found"].get<int>(), j["plan"]["lines_touching"].get<int>());
  EXPECT_LE(j["plan"]["median_checks"].get<double>(), j["planning_checks"].get<double>());
}

// The acceptance run: the built-in 'paper' preset with the fast method completes and prints the
// paper's table (generated into a scratch cache, so it runs from scratch).
TEST_F(Cli, EvalOnThePaperPresetPrintsTheTable) {
  const CommandResult r = lmk("eval --preset paper --method fast --threads 2 --cache " + path("c"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* setting : {"simple", "cluttered", "unconventional", "all"})
    EXPECT_NE(r.out.find(setting), std::string::npos) << setting;
  EXPECT_NE(r.out.find("17 scenes, 187 pairs"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace lmk
