#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Checks that every C++ file of the repository is formatted as .clang-format says (Google style,
# 100 columns): lists the files that are not and fails. `scripts/check-format.sh --fix` formats
# them instead. The test command (scripts/test.sh) runs the check first.
set -euo pipefail
cd "$(dirname "$0")/.."
clang_format=${CLANG_FORMAT:-clang-format}
mapfile -t files < <(git ls-files '*.h' '*.cpp')
if [ "${1:-}" = --fix ]; then
  "$clang_format" -i "${files[@]}"
  exit 0
fi
# One run over every file; each unformatted one is named in its messages ("FILE:LINE:COL: error").
mapfile -t unformatted < <("$clang_format" --dry-run --Werror "${files[@]}" 2>&1 |
                           sed -n 's/^\([^:]*\):[0-9]*:[0-9]*: error:.*/\1/p' | sort -u)
if [ ${#unformatted[@]} -ne 0 ]; then
  echo "check-format: ${#unformatted[@]} of ${#files[@]} files are not clang-formatted" \
       "(bash scripts/check-format.sh --fix):" >&2
  printf '  %s\n' "${unformatted[@]}" >&2
  exit 1
fi
echo "check-format: all ${#files[@]} C++ files are clang-formatted"
