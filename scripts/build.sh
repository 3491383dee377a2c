#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs the dependencies (if missing) and builds lmk in Release into ${LMK_BUILD_DIR:-build}.
# Extra arguments go to CMake's configure step, e.g. -DLMK_BUILD_BENCH=OFF.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
build=${LMK_BUILD_DIR:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build "$build" -j2
