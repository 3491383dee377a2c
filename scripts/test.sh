#!/usr/bin/env bash
# Quick start 2: install, build, and run the whole test suite (CTest, 2 jobs).
# Tests that need ../shared/data skip cleanly when it is absent.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
build=${LMK_BUILD_DIR:-build}
ctest --test-dir "$build" -j2 --output-on-failure --timeout 900
