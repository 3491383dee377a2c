#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Quick start 2: install, build and run every test CI runs.
#   1. the clang-format check (scripts/check-format.sh), the Release build with warnings as errors
#      and the whole suite (CTest, 2 jobs), the layering check among it;
#   2. the sanitizer build (clang-14: AddressSanitizer, UndefinedBehaviorSanitizer, libFuzzer
#      coverage) and the unit tests of the geometry, I/O, occupancy, registration, PbD and PR2
#      modules and of crash safety under it, with the fuzz targets' corpora;
#   3. a fuzz smoke run: each fuzz target for 5000 executions, seed 1 (scripts/fuzz.sh).
# Tests that need ../shared/data skip cleanly when it is absent. Timings: docs/reliability.md.
#
#   bash scripts/test.sh              all three (--all): what .ci/run runs
#   bash scripts/test.sh --suite      step 1 only
#   bash scripts/test.sh --sanitize   the sanitizer build and the whole suite under it
#   bash scripts/test.sh --tsan       a ThreadSanitizer build and the threaded tests under it
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:---all}
case "$mode" in
  --all|--suite|--sanitize|--tsan) ;;
  -h|--help) awk 'NR > 2 && /^#/ { sub(/^# ?/, ""); print; next } NR > 2 { exit }' "$0"; exit 0 ;;
  *) echo "test.sh: unknown option '$mode' (see --help)" >&2; exit 2 ;;
esac

# The sanitizer run of CI: the modules whose unit tests take minutes, not hours, under ASan (about
# 3 min on 2 cores), and the fuzz targets' corpora. The searches of test_landmark (a rotated-scene
# search alone takes 5 min under ASan), the dataset generation of test_eval, the CLI end to end
# and the six demo tasks run in the Release suite; `--sanitize` runs everything.
unit_modules=(test_geometry test_io test_occupancy test_registration test_pbd test_pr2 test_crash_safety)
unit_label="^($(IFS='|'; echo "${unit_modules[*]}")|fuzz)\$"
# The tests that run searches and evaluations on several threads, and their executables; and
# lmk serve's, whose HTTP threads, job pool and searches share its state (issue #34).
threaded='ThreadCount|DoNotDependOnThreads|Concurrent|Parallel|ServeTest|JobPool|AccessGuard'
threaded_modules=(test_geometry test_eval test_occupancy test_landmark test_serve)

# The ten slowest tests of the last CTest run in build directory $1, from CTest's own record of
# each test's time (a running average over the runs in that directory: in a fresh clone, this
# run's). Where the suite's time goes, on every run (issue #62).
slowest_tests() {
  local costs="$1/Testing/Temporary/CTestCostData.txt"
  [ -f "$costs" ] || return 0
  echo "test.sh: the ten slowest tests (s):"
  # The last stage reads to the end: `head` would close the pipe early, and with pipefail sort's
  # SIGPIPE (once the list outgrows the pipe's buffer) failed the whole run.
  awk 'NF == 3 && $3 ~ /^[0-9.]+$/ { printf "%8.1f  %s\n", $3, $1 }' "$costs" | sort -rn |
    awk 'NR <= 10'
}

run_suite() {
  bash scripts/install-deps.sh
  bash scripts/check-format.sh
  # CI's build treats warnings as errors (LMK_WERROR; the flags are set once, cmake/LmkTargets.cmake).
  bash scripts/build.sh -DLMK_WERROR=ON
  local build=${LMK_BUILD_DIR:-build} status=0
  ctest --test-dir "$build" -j2 --output-on-failure --timeout 900 || status=$?
  slowest_tests "$build"
  return "$status"
}

run_sanitized() {  # all | unit
  bash scripts/install-deps.sh
  local build=${LMK_SANITIZE_BUILD_DIR:-build-sanitize} selection=()
  bash scripts/configure-sanitize.sh "$build" -DLMK_WERROR=ON  # clang-14's warnings too
  if [ "$1" = unit ]; then
    cmake --build "$build" -j2 --target "${unit_modules[@]}" fuzz_all
    # Two tests take well over ten minutes under ASan (Eigen's small products are not inlined
    # there), seconds in Release, which runs them:
    # - the collision model's agreement with the real PR2 meshes checks 1,000 configurations
    #   against them exactly; here its STL reader is exercised by the StlMesh tests;
    # - looking where the arm would go unseen plans every motion three times over, with the
    #   planner; here MotionCheck's unseen-space and PlanCollisions' planner tests cover that code.
    local slow='CollisionModel\.AgreesWithTheFullDescriptionsMeshesNearATable'
    slow+='|LookAgainTest\.WhereTheArmWouldGoUnseenIsLookedAtFirst'
    selection=(-L "$unit_label" -E "^($slow)\$")
  else
    cmake --build "$build" -j2
  fi
  # Leaks are reported by the fuzz targets; the suite's processes are short and the libraries'
  # singletons (OpenVDB, TBB, PCL) would drown them.
  local status=0
  ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir "$build" -j2 --output-on-failure --timeout 1800 "${selection[@]}" ||
    status=$?
  slowest_tests "$build"
  return "$status"
}

run_tsan() {
  bash scripts/install-deps.sh
  local build=${LMK_TSAN_BUILD_DIR:-build-tsan}
  # oneTBB built with ThreadSanitizer, loaded in place of Debian's (see build-tbb-tsan.sh).
  local tbb
  tbb="$(realpath -m "$build")/tbb-tsan"  # absolute: it goes into LD_LIBRARY_PATH
  bash scripts/build-tbb-tsan.sh "$tbb"
  export LD_LIBRARY_PATH="$tbb/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  CMAKE_GENERATOR=${CMAKE_GENERATOR:-Ninja} \
    cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang-14 \
    -DCMAKE_CXX_COMPILER=clang++-14 -DLMK_TSAN=ON -DLMK_BUILD_BENCH=OFF -DLMK_BUILD_PYTHON=OFF \
    >/dev/null
  # The options apply to the build too: it runs each test executable to list its tests.
  export TSAN_OPTIONS="halt_on_error=1 suppressions=$PWD/tests/tsan.supp"
  cmake --build "$build" -j2 --target "${threaded_modules[@]}"
  ctest --test-dir "$build" -j2 --output-on-failure --timeout 1800 -R "$threaded"
}

timed() {  # label command...: runs it and says how long it took
  local start=$SECONDS
  "${@:2}"
  echo "test.sh: $1 took $(( (SECONDS - start) / 60 )) min $(( (SECONDS - start) % 60 )) s"
}

case "$mode" in
  --suite) timed "the Release suite" run_suite ;;
  --sanitize) timed "the sanitizer suite" run_sanitized all ;;
  --tsan) timed "the ThreadSanitizer tests" run_tsan ;;
  --all)
    timed "the Release suite" run_suite
    timed "the sanitizer unit tests" run_sanitized unit
    # A fixed seed and count: CI's run is the one run here (about a minute a target).
    timed "the fuzz smoke run" bash scripts/fuzz.sh --runs 5000 --seed 1
    ;;
esac
