// SPDX-License-Identifier: BSD-3-Clause
#include "tools/slurm_job.h"

#include <regex>

#include "lmk/geometry/error.h"
#include "lmk/geometry/version.h"

namespace lmk::cli {
namespace {

bool has_control_character(const std::string& text) {
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) return true;
  }
  return false;
}

// Throws unless `value` (of `option`) matches `pattern` and holds no control character.
void check_value(const std::string& option, const std::string& value, const std::regex& pattern,
                 const std::string& expected) {
  if (has_control_character(value) || !std::regex_match(value, pattern))
    throw Error("slurm eval: " + option + " '" + printable(value) + "' is not " + expected);
}

void check_text(const std::string& what, const std::string& value) {
  if (has_control_character(value))
    throw Error("slurm eval: " + what + " '" + printable(value) +
                "' holds a control character, which would reach the scripts");
}

std::string words(const std::vector<std::string>& args) {
  std::string out;
  for (const std::string& a : args) out += " " + shell_quote(a);
  return out;
}

// The "#SBATCH" header every script shares, then the script's own lines.
std::string header(const SlurmJob& job, const std::string& name, const std::string& what,
                   bool array, int cpus, const std::string& time) {
  const std::string log = (job.dir / "logs" / (name + (array ? "-%A_%a.out" : "-%j.out"))).string();
  std::string s = "#!/bin/bash\n# " + what + "\n# Written by lmk " + kVersion +
                  " (lmk slurm eval); see docs/cluster.md.\n";
  s += "#SBATCH --job-name=lmk-" + name + "\n";
  if (array) s += "#SBATCH --array=1-" + std::to_string(job.tasks) + "\n";
  s += "#SBATCH --cpus-per-task=" + std::to_string(cpus) + "\n";
  s += "#SBATCH --time=" + time + "\n";
  s += "#SBATCH --output=" + log + "\n";
  if (!job.partition.empty()) s += "#SBATCH --partition=" + job.partition + "\n";
  if (!job.account.empty()) s += "#SBATCH --account=" + job.account + "\n";
  if (!job.mem_per_cpu.empty()) s += "#SBATCH --mem-per-cpu=" + job.mem_per_cpu + "\n";
  for (const std::string& option : job.sbatch_options) s += "#SBATCH " + option + "\n";
  return s + "set -euo pipefail\n";
}

}  // namespace

void validate(const SlurmJob& job) {
  // sbatch's --time: MINUTES, MINUTES:SECONDS, HOURS:MINUTES:SECONDS, DAYS-HOURS,
  // DAYS-HOURS:MINUTES, DAYS-HOURS:MINUTES:SECONDS, or no limit.
  static const std::regex time(R"((\d+-\d+(:\d+){0,2}|\d+(:\d+){0,2}|UNLIMITED|INFINITE))");
  static const std::regex names(R"([A-Za-z0-9_.-]+(,[A-Za-z0-9_.-]+)*)");
  static const std::regex name(R"([A-Za-z0-9_.-]+)");
  static const std::regex size(R"(\d+[KMGT]?)");
  const std::string time_format =
      "a Slurm time (MINUTES, MINUTES:SECONDS, HOURS:MINUTES:SECONDS, "
      "DAYS-HOURS[:MINUTES[:SECONDS]] or UNLIMITED)";
  check_value("--time", job.time, time, time_format);
  check_value("--merge-time", job.merge_time, time, time_format);
  if (!job.partition.empty())
    check_value("--partition", job.partition, names, "a Slurm partition name (or a list of them)");
  if (!job.account.empty()) check_value("--account", job.account, name, "a Slurm account name");
  if (!job.mem_per_cpu.empty())
    check_value("--mem-per-cpu", job.mem_per_cpu, size, "a Slurm size (e.g. 2048, 2G)");
  for (const std::string& option : job.sbatch_options) {
    check_text("--sbatch", option);
    if (option.empty() || option.front() != '-')
      throw Error("slurm eval: --sbatch '" + option +
                  "' is not an sbatch option (it starts with '-', e.g. --sbatch=--qos=short)");
  }
  check_text("the job directory", job.dir.string());
  check_text("the cache", job.cache.string());
  check_text("the lmk executable's path", job.lmk);
  check_text("the dataset's path", job.dataset_dir.string());
  for (const std::string& a : job.eval_args) check_text("lmk eval's argument", a);
  for (const std::string& a : job.merge_args) check_text("lmk eval's argument", a);
  if (job.gen_args)
    for (const std::string& a : *job.gen_args) check_text("lmk gen's argument", a);
}

std::string shell_quote(const std::string& text) {
  const bool safe = !text.empty() && text.find_first_not_of(
                                         "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                         "0123456789_-./:=,+@%") == std::string::npos;
  if (safe) return text;
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

namespace {

// submit.sh: the chain, or a resubmission of some eval tasks and the merge after them.
std::string submit_script(const SlurmJob& job) {
  const std::string n = std::to_string(job.tasks);
  const std::string dataset_json = shell_quote((job.dataset_dir / "dataset.json").string());
  std::string s =
      "#!/bin/bash\n"
      "# Submits lmk's evaluation to Slurm: `bash submit.sh` submits every job, each after the "
      "one\n"
      "# before it succeeded (--dependency=afterok); `bash submit.sh 3,5` submits eval tasks 3 "
      "and 5\n"
      "# alone (after a failure: each computes only the pairs it lacks) and a merge after them.\n"
      "# Written by lmk " +
      std::string(kVersion) +
      " (lmk slurm eval); see docs/cluster.md.\n"
      "set -euo pipefail\n"
      "cd " +
      shell_quote(job.dir.string()) +
      "\n"
      "mkdir -p logs\n"
      "tasks=\"${1:-}\"\n"
      "after=\"\"\n";
  if (job.gen_args) {
    s += "if [ ! -f " + dataset_json +
         " ]; then\n"
         "  if [ -n \"$tasks\" ]; then\n"
         "    echo \"submit.sh: the dataset is not generated yet; run bash submit.sh without "
         "tasks\" >&2\n"
         "    exit 2\n"
         "  fi\n"
         "  gen=$(sbatch --parsable gen.sbatch)\n"
         "  gen_merge=$(sbatch --parsable --dependency=afterok:\"${gen%%;*}\" gen-merge.sbatch)\n"
         "  after=\"--dependency=afterok:${gen_merge%%;*}\"\n"
         "  echo \"generation: array job ${gen%%;*} (" +
         n +
         " tasks), then job ${gen_merge%%;*} writes the dataset\"\n"
         "fi\n";
  }
  s += "if [ -n \"$tasks\" ]; then\n"
       "  evaluation=$(sbatch --parsable $after --array=\"$tasks\" eval.sbatch)\n"
       "else\n"
       "  evaluation=$(sbatch --parsable $after eval.sbatch)\n"
       "fi\n"
       "merge=$(sbatch --parsable --dependency=afterok:\"${evaluation%%;*}\" merge.sbatch)\n"
       "echo \"evaluation: array job ${evaluation%%;*} (tasks ${tasks:-1-" +
       n +
       "}), then job ${merge%%;*} merges\"\n"
       "echo \"the table: \"" +
       shell_quote((job.dir / "table.txt").string()) +
       "\" once job ${merge%%;*} has run; logs in \"" + shell_quote((job.dir / "logs").string()) +
       "\n"
       "echo \"$evaluation $merge\" > last-submission\n";
  return s;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> slurm_scripts(const SlurmJob& job) {
  const std::string n = std::to_string(job.tasks);
  const std::string shard = " --shard \"${SLURM_ARRAY_TASK_ID}/" + n + "\"";
  const std::string lmk = shell_quote(job.lmk);
  const std::string cache = " --cache " + shell_quote(job.cache.string());
  std::vector<std::pair<std::string, std::string>> scripts;
  if (job.gen_args) {
    scripts.emplace_back("gen.sbatch",
                         header(job, "gen", "Renders shard K of " + n + " of the dataset's scenes.",
                                true, job.cpus_per_task, job.time) +
                             "exec " + lmk + " gen" + words(*job.gen_args) + shard + "\n");
    scripts.emplace_back("gen-merge.sbatch",
                         header(job, "gen-merge", "Writes dataset.json once every shard rendered.",
                                false, 1, job.merge_time) +
                             "exec " + lmk + " gen" + words(*job.gen_args) + " --merge\n");
  }
  scripts.emplace_back("eval.sbatch",
                       header(job, "eval",
                              "Evaluates shard K of " + n +
                                  " of the pairs into the shared cache; a rerun computes "
                                  "only the pairs it lacks.",
                              true, job.cpus_per_task, job.time) +
                           "exec " + lmk + " eval" + words(job.eval_args) + cache +
                           " --threads \"${SLURM_CPUS_PER_TASK:-" +
                           std::to_string(job.cpus_per_task) + "}\"" + shard + "\n");
  // The table is written under a temporary name and renamed: table.txt is whole or absent.
  const std::string table = shell_quote((job.dir / "table.txt").string());
  const std::string partial = shell_quote((job.dir / "table.txt.partial").string());
  scripts.emplace_back(
      "merge.sbatch",
      header(job, "merge",
             "Prints the table from the cache once every shard has run, or names the pairs "
             "missing.",
             false, 1, job.merge_time) +
          lmk + " eval" + words(job.eval_args) + cache + " --merge" + words(job.merge_args) +
          " > " + partial + "\nmv " + partial + " " + table + "\ncat " + table + "\n");

  scripts.emplace_back("submit.sh", submit_script(job));
  return scripts;
}

}  // namespace lmk::cli
