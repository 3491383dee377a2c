#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""No product function longer than the limit (docs/developing.md, "Style"): a long function is
split into named stages that return small results. Function extents come from Universal Ctags
(its `end` field), over the library folders, tools/ and python/; tests, benchmarks and generated
files are not product code.

  check_function_length.py [--root DIR] [--limit 80] [--list N]

Exits 1 naming each function over the limit; --list N prints the N longest either way. Exits 77
(CTest's skip) when Universal Ctags is not installed."""

import argparse
import os
import shutil
import subprocess
import sys

PRODUCT_DIRS = ["geometry", "occupancy", "registration", "landmark", "pbd", "pr2", "eval", "demos",
                "json", "ros", "serve", "tools", "python"]


def function_lengths(root):
    """(lines, file, name, first line) of every function and method ctags finds, longest first."""
    dirs = [d for d in PRODUCT_DIRS if os.path.isdir(os.path.join(root, d))]
    out = subprocess.run(
        ["ctags", "-R", "--languages=C++", "--kinds-C++=f", "--fields=+ne", "-x",
         "--_xformat=%{line} %{end} %{input} %{name}"] + dirs,
        cwd=root, check=True, capture_output=True, text=True).stdout
    found = []
    for line in out.splitlines():
        parts = line.split(" ", 3)
        if len(parts) != 4 or not parts[0].isdigit() or not parts[1].isdigit():
            continue  # a declaration without a body has no end
        first, end, path, name = int(parts[0]), int(parts[1]), parts[2], parts[3]
        found.append((end - first + 1, path, name, first))
    found.sort(key=lambda f: (-f[0], f[1], f[3]))
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=os.path.join(os.path.dirname(__file__), "..", ".."))
    parser.add_argument("--limit", type=int, default=80)
    parser.add_argument("--list", type=int, default=0, help="print the N longest functions")
    args = parser.parse_args()
    if shutil.which("ctags") is None or "Universal Ctags" not in subprocess.run(
            ["ctags", "--version"], capture_output=True, text=True).stdout:
        print("check_function_length: Universal Ctags is not installed (scripts/install-deps.sh)")
        return 77
    found = function_lengths(os.path.abspath(args.root))
    for lines, path, name, first in found[:args.list]:
        print(f"{lines:4d}  {path}:{first}  {name}")
    over = [f for f in found if f[0] > args.limit]
    for lines, path, name, first in over:
        print(f"check_function_length: {path}:{first}: {name} has {lines} lines "
              f"(at most {args.limit}): split it into named stages", file=sys.stderr)
    if not over:
        print(f"check_function_length: {len(found)} functions, none over {args.limit} lines")
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
