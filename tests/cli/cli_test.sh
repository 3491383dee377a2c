#!/usr/bin/env bash
# End-to-end checks of the lmk command line: exit codes, one-line errors, JSON output.
# Usage: cli_test.sh LMK_BINARY [SHARED_DATA_DIR]
set -u
lmk=$1
shared=${2:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
checks=0

fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# expect_exit CODE ARGS...: runs lmk; checks the exit code, and for errors that stderr is one line.
expect_exit() {
  local want=$1
  shift
  checks=$((checks + 1))
  "$lmk" "$@" >"$work/out" 2>"$work/err"
  local got=$?
  [ "$got" -eq "$want" ] || { fail "lmk $* exited $got, expected $want: $(cat "$work/err")"; return; }
  if [ "$want" -ne 0 ]; then
    [ "$(wc -l <"$work/err")" -eq 1 ] || fail "lmk $*: stderr is not one line: $(cat "$work/err")"
    grep -q '^lmk: error: ' "$work/err" || fail "lmk $*: stderr lacks 'lmk: error:': $(cat "$work/err")"
  fi
}

expect_exit 0 --help
expect_exit 0 --version
grep -q '^lmk [0-9]' "$work/out" || fail "--version does not print 'lmk X.Y.Z'"
expect_exit 2
expect_exit 2 no-such-subcommand
expect_exit 2 info
expect_exit 2 info "$work/missing.pcd"
echo "garbage" >"$work/garbage.pcd"
expect_exit 2 info "$work/garbage.pcd"
expect_exit 2 info "$work/cloud.obj"
expect_exit 2 convert "$work/missing.pcd" "$work/out.ply"

# The built-in scene, then info and convert on it.
expect_exit 0 gen "$work/scene.pcd" --seed 4
expect_exit 0 info "$work/scene.pcd" --json
python3 - "$work/out" <<'PY' || fail "info --json output is wrong"
import json, sys
j = json.load(open(sys.argv[1]))
assert sorted(j) == ["bounds", "fields", "finite_points", "height", "points", "sensor_origin", "width"], sorted(j)
assert j["points"] == 307200 and j["width"] == 640 and j["height"] == 480, j
assert 0 < j["finite_points"] < j["points"], j
assert j["fields"][:3] == ["x", "y", "z"], j["fields"]
assert all(lo <= hi for lo, hi in zip(j["bounds"]["min"], j["bounds"]["max"])), j["bounds"]
assert len(j["sensor_origin"]) == 3 and j["sensor_origin"][2] > 1.0, j["sensor_origin"]
PY
expect_exit 0 convert "$work/scene.pcd" "$work/scene.ply"
expect_exit 0 convert "$work/scene.ply" "$work/scene_ascii.pcd" --encoding ascii
expect_exit 0 info "$work/scene_ascii.pcd" --json
grep -q '"points": 307200' "$work/out" || fail "convert lost points"
expect_exit 2 convert "$work/scene.pcd" "$work/scene.obj"
expect_exit 2 convert "$work/scene.pcd" "$work/scene.pcd" --encoding lz4
[ ! -e "$work/scene.obj" ] || fail "a failed convert left a file behind"

if [ -n "$shared" ] && [ -f "$shared/pcl/milk_cartoon_all_small_clorox.pcd" ]; then
  expect_exit 0 info "$shared/pcl/milk_cartoon_all_small_clorox.pcd" --json
  python3 - "$work/out" <<'PY' || fail "milk scene info is wrong"
import json, sys
j = json.load(open(sys.argv[1]))
assert (j["points"], j["finite_points"], j["width"], j["height"]) == (307200, 241407, 640, 480), j
PY
else
  echo "skipping the real-data check: ../shared/data is absent"
fi

echo "$((checks - failures)) passed, $failures failed"
[ "$failures" -eq 0 ]
