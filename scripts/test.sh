#!/usr/bin/env bash
# Quick start 2: install, build and run every test CI runs.
#   1. the Release build and the whole suite (CTest, 2 jobs);
#   2. the sanitizer build (clang-14: AddressSanitizer, UndefinedBehaviorSanitizer, libFuzzer
#      coverage) and the unit tests under it: every test but the end-to-end runs of the CLI and of
#      the demo tasks, which the Release suite covers;
#   3. a fuzz smoke run: each fuzz target for 60 s (scripts/fuzz.sh).
# Tests that need ../shared/data skip cleanly when it is absent. Timings: docs/reliability.md.
#
#   bash scripts/test.sh              all three: what .ci/run runs
#   bash scripts/test.sh --suite      step 1 only
#   bash scripts/test.sh --sanitize   the sanitizer build and the whole suite under it
#   bash scripts/test.sh --tsan       a ThreadSanitizer build and the threaded tests under it
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:---suite}  # TODO(#17): all, once the sanitizer run passes
case "$mode" in
  --all|--suite|--sanitize|--tsan) ;;
  -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
  *) echo "test.sh: unknown option '$mode' (see --help)" >&2; exit 2 ;;
esac

# What the sanitizer run of CI leaves to the Release suite, each taking minutes under ASan: the
# end-to-end runs through the CLI binary and of the six demo tasks, the install test, and the
# tests that render hundreds of simulated frames to compare them with real ones (the renderer
# itself is tested under ASan by DepthSensor.* and ProjectorShadow.*).
end_to_end='^(Cli|CliLandmark)\.|^DemoTasks\.|^consumer_project$'
end_to_end+='|^SensorValidation\.(SimulatedKinect|FlyingPixels|DepthEdge)'
end_to_end+='|^SceneTypes\.GroundTruthBoxesHoldWhatTheSensorSees$'
# The tests that run searches and evaluations on several threads.
threaded='ThreadCount|DoNotDependOnThreads|Concurrent|Parallel'

run_suite() {
  bash scripts/build.sh
  ctest --test-dir "${LMK_BUILD_DIR:-build}" -j2 --output-on-failure --timeout 900
}

run_sanitized() {  # [ctest arguments...]
  bash scripts/install-deps.sh
  local build=${LMK_SANITIZE_BUILD_DIR:-build-sanitize}
  bash scripts/configure-sanitize.sh "$build"
  cmake --build "$build" -j2
  # Leaks are reported by the fuzz targets; the suite's processes are short and the libraries'
  # singletons (OpenVDB, TBB, PCL) would drown them.
  ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir "$build" -j2 --output-on-failure --timeout 1800 "$@"
}

run_tsan() {
  bash scripts/install-deps.sh
  local build=${LMK_TSAN_BUILD_DIR:-build-tsan}
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang-14 \
    -DCMAKE_CXX_COMPILER=clang++-14 -DLMK_TSAN=ON -DLMK_BUILD_BENCH=OFF >/dev/null
  cmake --build "$build" -j2
  TSAN_OPTIONS="halt_on_error=1 suppressions=$PWD/tests/tsan.supp" \
    ctest --test-dir "$build" -j2 --output-on-failure --timeout 1800 -R "$threaded"
}

timed() {  # label command...: runs it and says how long it took
  local start=$SECONDS
  "${@:2}"
  echo "test.sh: $1 took $(( (SECONDS - start) / 60 )) min $(( (SECONDS - start) % 60 )) s"
}

case "$mode" in
  --suite) timed "the Release suite" run_suite ;;
  --sanitize) timed "the sanitizer suite" run_sanitized ;;
  --tsan) timed "the ThreadSanitizer tests" run_tsan ;;
  --all)
    timed "the Release suite" run_suite
    timed "the sanitizer unit tests" run_sanitized -E "$end_to_end"
    timed "the fuzz smoke run" bash scripts/fuzz.sh 60
    ;;
esac
