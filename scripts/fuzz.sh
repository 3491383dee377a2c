#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Fuzzes lmk's readers of user files with libFuzzer (clang-14) under ASan and UBSan.
#
#   bash scripts/fuzz.sh [SECONDS]     each target for SECONDS (default 60), two at a time
#   bash scripts/fuzz.sh --runs N      each target for N executions
#   --seed S                           libFuzzer's random seed (default: random); with --runs and
#                                      a fresh build directory a run is reproducible (CI's smoke)
#
# Targets: fuzz_pcd, fuzz_ply, fuzz_xyz (cloud readers), fuzz_landmark (.lmk as a user hands it
# over), fuzz_vdb_layout (lmk's walk of a landmark's OpenVDB container, behind the checksum),
# fuzz_program, fuzz_dataset, fuzz_depth_png and fuzz_depth_pgm (RGB-D depth images), and
# fuzz_serve_request (lmk serve's access guard and API handlers). Each starts from its committed seed corpus (tests/fuzz/corpus/TARGET) plus what
# earlier runs found (BUILD/fuzz/corpus/TARGET). A crash, sanitizer report, leak, timeout (10 s)
# or single allocation over 2 GB is a finding: its input is kept in BUILD/fuzz/findings/TARGET/,
# the script prints it and exits 1. Put each finding, once fixed, into
# tests/fuzz/regressions/TARGET/: the suite replays it from then on.
# The build goes to ${LMK_SANITIZE_BUILD_DIR:-build-sanitize}, shared with scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=60
runs=
seed=0  # libFuzzer's 0: a random seed
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs=${2:?--runs needs a count}; shift ;;
    --seed) seed=${2:?--seed needs a number}; shift ;;
    -h|--help) awk 'NR > 2 && /^#/ { sub(/^# ?/, ""); print; next } NR > 2 { exit }' "$0"; exit 0 ;;
    *) seconds=$1 ;;
  esac
  shift
done
for n in "${runs:-$seconds}" "$seed"; do
  if ! [[ "$n" =~ ^[0-9]+$ ]]; then
    echo "fuzz.sh: '$n' is not a whole number (see --help)" >&2
    exit 2
  fi
done

bash scripts/install-deps.sh
build=${LMK_SANITIZE_BUILD_DIR:-build-sanitize}
bash scripts/configure-sanitize.sh "$build"
cmake --build "$build" -j2 --target fuzz_all
targets=()
for binary in "$build"/tests/fuzz/fuzz_*; do
  [ -x "$binary" ] && [ -f "$binary" ] && targets+=("$(basename "$binary")")
done

fuzz_one() {
  local target=$1 corpus=${target#fuzz_}
  local work="$build/fuzz/corpus/$target" findings="$build/fuzz/findings/$target/"
  rm -rf "$findings"  # this run's findings only; earlier ones are in the regressions or fixed
  mkdir -p "$work" "$findings"
  local budget=(-max_total_time="$seconds")
  [ -n "$runs" ] && budget=(-runs="$runs")
  # ASan's leak check stays on; OpenVDB's and TBB's process-lifetime singletons are not leaks.
  LSAN_OPTIONS=suppressions=$PWD/tests/fuzz/lsan.supp ASAN_OPTIONS=detect_leaks=1 \
    "$build/tests/fuzz/$target" "${budget[@]}" -seed="$seed" -timeout=10 -rss_limit_mb=4096 \
    -malloc_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$findings" \
    "$work" "tests/fuzz/corpus/$corpus" >"$build/fuzz/$target.log" 2>&1
}

mkdir -p "$build/fuzz"
status=0
pids=()
for target in "${targets[@]}"; do
  fuzz_one "$target" &
  pids+=($!)
  if [ ${#pids[@]} -eq 2 ]; then  # two at a time: one per core
    wait "${pids[0]}" || status=1
    wait "${pids[1]}" || status=1
    pids=()
  fi
done
for pid in "${pids[@]}"; do wait "$pid" || status=1; done

printf '%-14s %12s %8s %8s %8s %9s\n' target executions exec/s coverage corpus findings
for target in "${targets[@]}"; do
  log="$build/fuzz/$target.log"
  stat() { grep -o "^stat::$1: *[0-9]*" "$log" | grep -o '[0-9]*$' || echo '?'; }
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo '?')
  corpus=$(find "$build/fuzz/corpus/$target" -type f | wc -l)
  found=$(find "$build/fuzz/findings/$target" -type f | wc -l)
  printf '%-14s %12s %8s %8s %8s %9s\n' "$target" "$(stat number_of_executed_units)" \
    "$(stat average_exec_per_sec)" "$cov" "$corpus" "$found"
  if [ "$found" -gt 0 ]; then
    status=1
    grep -m1 -E 'ERROR|runtime error|deadly signal|out-of-memory|timeout' "$log" || true
    find "$build/fuzz/findings/$target" -type f
  fi
done
[ $status -eq 0 ] && echo "fuzz.sh: no findings" || echo "fuzz.sh: findings above (logs in $build/fuzz/)" >&2
exit $status
