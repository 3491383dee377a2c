#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# This build's search speed against another build's, measured the way issues #48 and #63 set their
# bars: the two run alternately, ROUNDS rounds, and only each round's ratio counts (this machine's
# speed drifts by a quarter from one hour to the next).
#   scripts/compare-speed.sh OTHER_LMK [ROUNDS] [OTHER_PAPER_DATASET THIS_PAPER_DATASET]
# Each round: `lmk bench --repeats 30 --reference-seeds 1` (the milk frame, two threads) with each
# build; with the two datasets, also `lmk eval --no-cache --threads 1` of `paper` with each (each
# build on a dataset it generated itself, `lmk gen D --preset paper`: an older build may not read
# this one's landmark files). Prints the medians and the ratios, this build over the other.
# Both builds get LMK_SHARED_DATA (default ../shared/data): a build that finds no shared data
# benches a rendered frame instead, so the script refuses when the two benched different workloads,
# and when the two evaluations' pairs or seeds differ.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 1 ] || [ $# -eq 3 ] || [ $# -gt 4 ]; then
  echo "usage: scripts/compare-speed.sh OTHER_LMK [ROUNDS] [OTHER_PAPER_DATASET THIS_PAPER_DATASET]" >&2
  exit 2
fi
other=$1
rounds=${2:-3}
this=${LMK:-build/tools/lmk}
export LMK_SHARED_DATA=${LMK_SHARED_DATA:-$(pwd)/../shared/data}
for tool in "$other" "$this"; do
  [ -x "$tool" ] || { echo "compare-speed: $tool is not an executable lmk" >&2; exit 2; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

for round in $(seq 1 "$rounds"); do
  for side in other this; do
    if [ $side = other ]; then tool=$other; else tool=$this; fi
    # Their own progress and summaries stay in a log, shown if a run fails.
    "$tool" bench --repeats 30 --reference-seeds 1 --json "$work/bench_$side.json" \
      >"$work/log" 2>&1 || { cat "$work/log" >&2; exit 1; }
    if [ $# -eq 4 ]; then
      if [ $side = other ]; then dataset=$3; else dataset=$4; fi
      "$tool" eval --dataset "$dataset" --no-cache --threads 1 --timings \
        --json "$work/paper_$side.json" >"$work/log" 2>&1 || { cat "$work/log" >&2; exit 1; }
    fi
  done
  python3 - "$work" "$round" <<'EOF'
import json, statistics, sys
work, round_ = sys.argv[1], sys.argv[2]
def load(name):
    with open(f"{work}/{name}.json") as f:
        return json.load(f)
other, this = load("bench_other"), load("bench_this")
if other["workload"] != this["workload"]:
    sys.exit(f"compare-speed: the builds benched different workloads: '{other['workload']}' "
             f"against '{this['workload']}' (is LMK_SHARED_DATA right?)")
o, t = other["fast"], this["fast"]
ms = lambda d, k: 1000.0 * d["median_seconds_" + k]
stages = lambda d: ", ".join(f"{k} {ms(d, k):.1f}" for k in ("preprocess", "vote", "coarse", "fine"))
print(f"round {round_}: bench {ms(o, 'per_search'):.1f} / {ms(t, 'per_search'):.1f} ms "
      f"({ms(t, 'per_search') / ms(o, 'per_search'):.3f}x); other: {stages(o)}; this: {stages(t)}")
try:
    other, this = load("paper_other"), load("paper_this")
except FileNotFoundError:
    sys.exit(0)
seeds = lambda d: {(p["scene"], p["landmark"]): p["seeds"] for p in d["pairs"]}
if seeds(other) != seeds(this):
    sys.exit("compare-speed: the two evaluations searched different pairs or seeds")
median = lambda d: statistics.median(p["seconds"] for p in d["pairs"])
print(f"round {round_}: paper {median(other):.4f} / {median(this):.4f} s per search "
      f"({median(this) / median(other):.3f}x), {len(this['pairs'])} pairs")
EOF
done
