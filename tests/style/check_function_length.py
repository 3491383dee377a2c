#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""No product function longer than the limit, and no source file longer than its own
(docs/developing.md, "Style"): a long function is split into named stages that return small
results, a long file into files of one subject each. Function extents come from Universal Ctags
(its `end` field), over the library folders, tools/ and python/; tests, benchmarks and generated
files are not product code. The file limit holds for tests and benchmarks too.

  check_function_length.py [--root DIR] [--limit 80] [--file-limit 600] [--list N]

Exits 1 naming each function and file over its limit; --list N prints the N longest functions
either way. Exits 77 (CTest's skip) when Universal Ctags is not installed."""

import argparse
import os
import re
import shutil
import subprocess
import sys

# tools/ (the CLI) and python/ are product code beside the libraries.
APPLICATION_DIRS = ["tools", "python"]


def product_dirs(root):
    """Every library folder (its CMakeLists.txt makes a target lmk::NAME), then tools/ and
    python/: read from the tree, so a new module is checked without being listed here."""
    libraries = []
    for name in sorted(os.listdir(root)):
        cmake = os.path.join(root, name, "CMakeLists.txt")
        if not os.path.isfile(cmake):
            continue
        with open(cmake, encoding="utf-8") as f:
            if re.search(r"lmk_add_library\(\s*" + name + r"\b|add_library\(lmk_" + name + r"\b",
                         f.read()):
                libraries.append(name)
    return libraries + [d for d in APPLICATION_DIRS if os.path.isdir(os.path.join(root, d))]


def function_lengths(root, dirs):
    """(lines, file, name, first line) of every function and method ctags finds in `dirs`,
    longest first."""
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


# Source files, by their endings; folders of test and benchmark code beside the product's.
SOURCE_ENDINGS = (".cpp", ".h", ".py")
TEST_DIRS = ["tests", "bench"]


def file_lengths(root, dirs):
    """(lines, file) of every source file in `dirs`, longest first."""
    found = []
    for top in dirs:
        for folder, _, files in os.walk(os.path.join(root, top)):
            for name in files:
                if name.endswith(SOURCE_ENDINGS):
                    path = os.path.join(folder, name)
                    with open(path, encoding="utf-8", errors="replace") as f:
                        found.append((sum(1 for _ in f), os.path.relpath(path, root)))
    return sorted(found, reverse=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=os.path.join(os.path.dirname(__file__), "..", ".."))
    parser.add_argument("--limit", type=int, default=80)
    parser.add_argument("--file-limit", type=int, default=600)
    parser.add_argument("--list", type=int, default=0, help="print the N longest functions")
    args = parser.parse_args()
    if shutil.which("ctags") is None or "Universal Ctags" not in subprocess.run(
            ["ctags", "--version"], capture_output=True, text=True).stdout:
        print("check_function_length: Universal Ctags is not installed (scripts/install-deps.sh)")
        return 77
    root = os.path.abspath(args.root)
    product = product_dirs(root)
    found = function_lengths(root, product)
    for lines, path, name, first in found[:args.list]:
        print(f"{lines:4d}  {path}:{first}  {name}")
    over = [f for f in found if f[0] > args.limit]
    for lines, path, name, first in over:
        print(f"check_function_length: {path}:{first}: {name} has {lines} lines "
              f"(at most {args.limit}): split it into named stages", file=sys.stderr)
    if not over:
        print(f"check_function_length: {len(found)} functions, none over {args.limit} lines")
    tests = [d for d in TEST_DIRS if os.path.isdir(os.path.join(root, d))]
    files = file_lengths(root, product + tests)
    long_files = [f for f in files if f[0] > args.file_limit]
    for lines, path in long_files:
        print(f"check_function_length: {path} has {lines} lines (at most {args.file_limit}): "
              f"split it into files of one subject each", file=sys.stderr)
    if not long_files:
        print(f"check_function_length: {len(files)} source files, none over {args.file_limit} "
              f"lines")
    return 1 if over or long_files else 0


if __name__ == "__main__":
    sys.exit(main())
