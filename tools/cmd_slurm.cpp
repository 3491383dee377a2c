// SPDX-License-Identifier: BSD-3-Clause
// lmk slurm eval [OPTIONS] -- [EVAL ARGS]: writes (and with --submit submits) an evaluation as a
// chain of Slurm jobs (tools/slurm_job.h, docs/cluster.md). The arguments after "--" are those of
// `lmk eval` and are checked as it checks them before anything is written.

#include <unistd.h>

#include <array>
#include <cstdio>
#include <memory>
#include <set>

#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/error.h"
#include "tools/cli_common.h"
#include "tools/slurm_job.h"

namespace lmk::cli {
namespace {

namespace fs = std::filesystem;

struct SlurmOptions {
  SlurmJob job;
  std::string dir = "lmk-slurm";
  std::string cache, lmk;
  bool submit = false;
  std::vector<std::string> eval_args;
};

// The arguments without the options named in `with_value` (and their values, as "--x v" or
// "--x=v") and the flags in `flags`; what was removed goes into `removed` when given.
std::vector<std::string> without(const std::vector<std::string>& args,
                                 const std::set<std::string>& with_value,
                                 const std::set<std::string>& flags,
                                 std::vector<std::string>* removed = nullptr) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string name = args[i].substr(0, args[i].find('='));
    const bool joined = name.size() < args[i].size();
    if (flags.count(args[i])) {
      if (removed) removed->push_back(args[i]);
    } else if (with_value.count(name)) {
      if (removed) removed->push_back(args[i]);
      if (!joined && i + 1 < args.size()) {
        if (removed) removed->push_back(args[i + 1]);
        ++i;
      }
    } else {
      out.push_back(args[i]);
    }
  }
  return out;
}

// The value of option `name` in `args` ("--x v" or "--x=v"), or nothing.
std::optional<std::string> value_of(const std::vector<std::string>& args, const std::string& name) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == name && i + 1 < args.size()) return args[i + 1];
    if (args[i].rfind(name + "=", 0) == 0) return args[i].substr(name.size() + 1);
  }
  return std::nullopt;
}

// Checks the eval arguments exactly as `lmk eval` parses them, without running anything.
void check_eval_args(const std::vector<std::string>& args) {
  CLI::App scratch;
  const Subcommand eval = add_eval(scratch);
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  reversed.push_back("eval");
  try {
    scratch.parse(reversed);
  } catch (const CLI::ParseError& e) {
    throw Error(std::string("slurm eval: the arguments for lmk eval: ") + e.what());
  }
  for (const char* own : {"--shard", "--merge", "--cache", "--no-cache", "--threads"}) {
    if (eval.app->get_option(own)->count() > 0) {
      throw Error(std::string("slurm eval: ") + own +
                  " is the job's to set (--tasks, --cache, --cpus-per-task); leave it out of the "
                  "eval arguments");
    }
  }
}

// This executable, for the batch scripts: the tasks run the very lmk that wrote them.
std::string this_executable() {
  std::array<char, 4096> path{};
  const ssize_t n = ::readlink("/proc/self/exe", path.data(), path.size() - 1);
  if (n <= 0) throw Error("slurm eval: cannot tell where lmk is; give --lmk PATH");
  return std::string(path.data(), static_cast<std::size_t>(n));
}

// The merge's arguments: the user's --json and --report made absolute (the merge runs in the job
// directory), defaulting to evaluation.json and report/ there.
void absolute_merge_outputs(SlurmJob& job) {
  for (std::size_t i = 0; i + 1 < job.merge_args.size(); ++i) {
    if (job.merge_args[i] == "--json" || job.merge_args[i] == "--report")
      job.merge_args[i + 1] = fs::absolute(job.merge_args[i + 1]).lexically_normal().string();
  }
  for (std::string& a : job.merge_args) {
    for (const std::string option : {"--json=", "--report="}) {
      if (a.rfind(option, 0) == 0)
        a = option + fs::absolute(a.substr(option.size())).lexically_normal().string();
    }
  }
  if (!value_of(job.merge_args, "--json"))
    job.merge_args.insert(job.merge_args.end(), {"--json", (job.dir / "evaluation.json").string()});
  if (!value_of(job.merge_args, "--report"))
    job.merge_args.insert(job.merge_args.end(), {"--report", (job.dir / "report").string()});
}

// The dataset the tasks evaluate: the user's --dataset, or a preset the job's own array generates
// into the job directory (never every task). Takes its arguments out of `shared`; returns what it
// is, for the summary.
std::string choose_dataset(SlurmJob& job, std::vector<std::string>& shared) {
  if (const auto dataset = value_of(shared, "--dataset")) {
    job.dataset_dir = fs::absolute(*dataset).lexically_normal();
    if (!fs::is_regular_file(job.dataset_dir / "dataset.json"))
      throw Error("slurm eval: " + (job.dataset_dir / "dataset.json").string() + " does not exist");
    shared = without(shared, {"--dataset"}, {});
    return "dataset " + job.dataset_dir.string();
  }
  std::vector<std::string> preset_args;
  shared =
      without(shared, {"--preset", "--seeds", "--first-seed", "--types"}, {"--hard"}, &preset_args);
  const std::string preset = value_of(preset_args, "--preset").value_or("paper");
  job.dataset_dir = job.dir / "dataset";
  std::vector<std::string> gen = {"--preset", preset, job.dataset_dir.string()};
  for (const char* option : {"--seeds", "--types"}) {
    if (const auto v = value_of(preset_args, option)) gen.insert(gen.end(), {option, *v});
  }
  if (const auto v = value_of(preset_args, "--first-seed")) gen.insert(gen.end(), {"--seed", *v});
  for (const std::string& a : preset_args) {
    if (a == "--hard") gen.push_back(a);
  }
  job.gen_args = gen;
  return "preset " + preset + " (generated by the job into " + job.dataset_dir.string() + ")";
}

// The job's scripts, written executable into its directory, and what they are.
void write_job_scripts(const SlurmJob& job, const std::string& what) {
  std::error_code ec;
  fs::create_directories(job.dir / "logs", ec);
  if (ec)
    throw Error("slurm eval: cannot create " + (job.dir / "logs").string() + ": " + ec.message());
  const auto scripts = slurm_scripts(job);
  for (const auto& [name, text] : scripts) {
    write_text_atomically(job.dir / name, text);
    fs::permissions(job.dir / name, fs::perms::owner_exec | fs::perms::group_exec,
                    fs::perm_options::add);
  }
  std::printf("wrote the Slurm jobs of an evaluation of %s into %s:\n", what.c_str(),
              job.dir.string().c_str());
  for (const auto& [name, text] : scripts) std::printf("  %s\n", name.c_str());
  std::printf(
      "%d shards, %d CPUs and %s each; results in %s, the table in %s once the merge has run\n",
      job.tasks, job.cpus_per_task, job.time.c_str(), job.cache.string().c_str(),
      (job.dir / "table.txt").string().c_str());
}

int run_slurm_eval(SlurmOptions& o) {
  SlurmJob& job = o.job;
  check_eval_args(o.eval_args);
  job.dir = fs::absolute(o.dir).lexically_normal();
  job.cache = o.cache.empty() ? job.dir / "cache" : fs::absolute(o.cache).lexically_normal();
  job.lmk = o.lmk.empty() ? this_executable() : fs::absolute(o.lmk).string();
  if (::access(job.lmk.c_str(), X_OK) != 0)
    throw Error("slurm eval: " + job.lmk + " is no program");

  // The merge's own options; every task gets the dataset and the search settings.
  std::vector<std::string> shared =
      without(o.eval_args, {"--json", "--report", "--by"}, {"--timings"}, &job.merge_args);
  absolute_merge_outputs(job);
  const std::string what = choose_dataset(job, shared);
  job.eval_args = {"--dataset", job.dataset_dir.string()};
  job.eval_args.insert(job.eval_args.end(), shared.begin(), shared.end());

  validate(job);
  write_job_scripts(job, what);
  const std::string submit = "bash " + shell_quote((job.dir / "submit.sh").string());
  if (!o.submit) {
    std::printf("submit with: %s    (a failed task K alone: %s K)\n", submit.c_str(),
                submit.c_str());
    return kOk;
  }
  std::fflush(stdout);
  if (std::system("command -v sbatch > /dev/null 2>&1") != 0) {
    throw Error(
        "slurm eval: sbatch is not on the PATH (is this a Slurm login node?); the scripts "
        "are written, submit them with " +
        submit + " where it is");
  }
  const int status = std::system(submit.c_str());
  if (status != 0) throw Error("slurm eval: " + submit + " failed; see the message above");
  return kOk;
}

}  // namespace

Subcommand add_slurm(CLI::App& app) {
  auto o = std::make_shared<SlurmOptions>();
  CLI::App* slurm = app.add_subcommand("slurm", "Run lmk's batch work on a Slurm cluster");
  slurm->require_subcommand(1);
  CLI::App* sub = slurm->add_subcommand(
      "eval",
      "Write (and with --submit submit) an evaluation as Slurm jobs: an array of shards, then a "
      "merge that depends on it; give lmk eval's arguments after --");
  sub->add_option("--dir", o->dir, "Job directory, on a filesystem every node shares")
      ->capture_default_str();
  sub->add_option("--tasks", o->job.tasks, "Array tasks: shards of the generation and evaluation")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--cpus-per-task", o->job.cpus_per_task, "CPUs of each task (its --threads)")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  sub->add_option("--time", o->job.time, "Time limit of each array task (Slurm's format)")
      ->capture_default_str();
  sub->add_option("--merge-time", o->job.merge_time, "Time limit of the merges")
      ->capture_default_str();
  sub->add_option("--partition", o->job.partition, "Slurm partition");
  sub->add_option("--account", o->job.account, "Slurm account");
  sub->add_option("--mem-per-cpu", o->job.mem_per_cpu, "Memory per CPU (Slurm's format, e.g. 2G)");
  sub->add_option("--sbatch", o->job.sbatch_options,
                  "A further #SBATCH option for every job, e.g. --sbatch=--qos=short (repeatable)")
      ->allow_extra_args(false);  // one value per --sbatch: what follows is lmk's
  sub->add_option("--cache", o->cache, "Evaluation cache every task shares (default DIR/cache)");
  sub->add_option("--lmk", o->lmk, "The lmk the tasks run (default: this one)");
  sub->add_flag("--submit", o->submit, "Also submit the jobs (runs DIR/submit.sh)");
  sub->add_option("eval_args", o->eval_args, "After --: lmk eval's arguments (dataset, settings)");
  return {slurm, [o] { return run_slurm_eval(*o); }};
}

}  // namespace lmk::cli
