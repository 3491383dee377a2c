#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# A walk through one landmark: render a tabletop scene with the simulated Kinect, capture the carton
# on it as a landmark, and find it again with the fast search.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh --tool
build=${LMK_BUILD_DIR:-build}
lmk="$build/tools/lmk"
out="$build/demo"
mkdir -p "$out"
"$lmk" --version
echo
"$lmk" gen "$out/tabletop.pcd" --seed 1
echo
"$lmk" info "$out/tabletop.pcd"
echo
# The carton of seed 1 as lmk gen prints it (centre, 7 x 7 x 19 cm, yaw -156 deg), drawn with 2 cm
# of free space around and above it, and its bottom just above the table top. The scene is in the
# world frame, z up. Capture searches the new landmark in its own scene and warns that the table's
# square leg looks like it too, naming each place: seen from this camera, the leg is a 7 x 7 cm post whose top is
# hidden, which is exactly what the carton's visible faces are.
"$lmk" capture "$out/tabletop.pcd" --box-center -0.301 0.236 0.826 --box-rpy 0 0 -156 \
  --box-size 0.11 0.11 0.21 --name carton -o "$out/carton.lmk" --base-frame
"$lmk" landmark show "$out/carton.lmk"
echo
# The default fast search. Expect the carton first, then the leg the check warned about (the
# carton's visible faces fit the 7 cm post at more than one height). The
# paper's reference search (--method reference) takes about a minute here with 150 seeds.
"$lmk" find "$out/tabletop.pcd" "$out/carton.lmk" --base-frame
