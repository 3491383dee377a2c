// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The batch scripts of `lmk slurm eval` (docs/cluster.md): an evaluation as a chain of Slurm jobs,
// written into one job directory on a filesystem every node shares.
//
//   gen.sbatch        (preset only) an array of N tasks, `lmk gen --preset ... --shard K/N`
//   gen-merge.sbatch  (preset only) after it: `lmk gen ... --merge` writes dataset.json
//   eval.sbatch       an array of N tasks, `lmk eval ... --shard K/N` into the shared cache
//   merge.sbatch      after it (afterok): `lmk eval ... --merge`, the table into table.txt
//   submit.sh         submits them in order with --dependency=afterok; `submit.sh 3,5` submits
//                     eval tasks 3 and 5 alone and a merge after them
//
// Every task is a whole lmk command: no distribution layer of lmk's own, the scheduler does it.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace lmk::cli {

struct SlurmJob {
  std::filesystem::path dir;      ///< the job directory (absolute)
  std::filesystem::path cache;    ///< the evaluation cache every task shares (absolute)
  std::string lmk;                ///< the lmk executable the tasks run (absolute)
  int tasks = 8;                  ///< array size: shards of the generation and of the evaluation
  int cpus_per_task = 2;          ///< also each task's --threads
  std::string time = "02:00:00";  ///< each array task's time limit
  std::string merge_time = "00:30:00";  ///< the merges' time limit
  std::string partition, account, mem_per_cpu;
  std::vector<std::string> sbatch_options;  ///< further "#SBATCH" options, as given

  /// Preset only: the `lmk gen` arguments after "gen" that write the dataset into dataset_dir.
  std::optional<std::vector<std::string>> gen_args;
  std::filesystem::path dataset_dir;  ///< where the evaluated dataset is (or will be)
  /// The `lmk eval` arguments after "eval" that every task shares: dataset and search settings.
  std::vector<std::string> eval_args;
  /// Only the merge's: --json, --report, --by, --timings (defaults: evaluation.json, report/).
  std::vector<std::string> merge_args;
};

/// Throws lmk::Error naming the option unless every value that reaches a script is safe there:
/// --time and --merge-time in Slurm's time formats, --partition and --account Slurm names,
/// --mem-per-cpu a Slurm size, --sbatch options starting with '-', and no control character in
/// any of them, in the paths or in lmk eval's arguments (a newline would end an "#SBATCH" line
/// and start a line of the script).
void validate(const SlurmJob& job);

/// `text` as one word of a POSIX shell: as is when it holds only safe characters, else in single
/// quotes.
std::string shell_quote(const std::string& text);

/// The file names and contents of the job's scripts, in submission order, submit.sh last.
std::vector<std::pair<std::string, std::string>> slurm_scripts(const SlurmJob& job);

}  // namespace lmk::cli
