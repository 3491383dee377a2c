#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Quick start 3: the web interface on built-in data. Builds lmk, writes the demo tabletop (carton,
# cup, ball) and the paper's tool-rack task (its scenes, landmarks and two programs), and serves
# them at http://127.0.0.1:8080/ until Ctrl-C (docs/serve.md); open the address it prints, which
# carries the server's token. Extra arguments go to `lmk serve`
# (--port 9000, say).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh --tool
build=${LMK_BUILD_DIR:-build}
lmk="$build/tools/lmk"
out="$build/serve-demo"
mkdir -p "$out"
[ -f "$out/tabletop.pcd" ] || "$lmk" gen "$out/tabletop.pcd" --seed 1
[ -f "$out/task1/pick_tool.json" ] || "$lmk" pbd demo-tasks --task 1 --save "$out" >/dev/null
echo
# Every scene is in the robot's base frame (z up). Captures go beside the task's landmarks.
exec "$lmk" serve "$out/tabletop.pcd" "$out"/task1/*.pcd --landmarks "$out/task1" \
  --programs "$out/task1" --base-frame "$@"
