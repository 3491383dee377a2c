#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""lmk's layering rule, checked on the includes of the source tree (docs/developing.md).

Each module folder is one layer, and a module includes only its own headers and those of the
layers below it:

    geometry < json < occupancy < registration < landmark < search < pbd < pr2 < sim < datasets
             < eval < demos < ros, serve < tools, python

Modules of one layer (ros and serve; tools and python) do not include each other. A module's
detail/ headers (in its folder or any subfolder of it) are its own: no other module includes them (tests and benchmarks, which look
inside on purpose, may). What a module shares with the layers above lies in its folder or in its
internal/ folder (shared within lmk, not installed). An installed header (any header of an
installed module outside detail/ and internal/, search/metrics/error_metrics.h too) includes no internal/ or detail/ header, which a consumer of the installed lmk
would not find. The evaluation's core (searching and scoring pairs, EVAL_CORE) includes none of
the reports built on it (ABOVE_EVAL_CORE).

Usage:
    check_layering.py [--root DIR]       exit 1 and one line per violation, if there are any
    check_layering.py --counts           the include count per module pair, as a Markdown table
    check_layering.py --check-docs FILE  exit 1 when FILE's counts table (between the markers
                                         below) is not the tree's
    check_layering.py --write-docs FILE  write the tree's counts table into FILE
    check_layering.py --self-test        plants each kind of violation and checks that it is seen
"""

import argparse
import os
import re
import sys

LAYERS = [["geometry"], ["json"], ["occupancy"], ["registration"], ["landmark"], ["search"],
          ["pbd"], ["pr2"], ["sim"], ["datasets"], ["eval"], ["demos"], ["ros", "serve"],
          ["tools", "python"]]
LEVEL = {module: level for level, layer in enumerate(LAYERS) for module in layer}
# Folders above every layer, allowed any include and any module's detail/.
ABOVE_ALL = ["tests", "bench"]
# Modules whose top-level headers are not installed: json/ (header-only, internal) and serve/
# (the lmk tool's own); tools/ and python/ install no headers.
NOT_INSTALLED = ["json", "serve", "tools", "python"]
# The evaluation's core: the pairs searched and scored, and cached (the datasets they come from
# lie a layer below). The reports built on it (the explanation, the ablation, their JSON) lie
# above it.
EVAL_CORE = ["eval/evaluation.h", "eval/evaluation.cpp", "eval/evaluation_protocol.h",
             "eval/evaluation_protocol.cpp", "eval/internal/pair_result_json.h",
             "eval/pair_result_json.cpp", "eval/detail/pair_cache.h", "eval/detail/pair_cache.cpp"]
PRIVATE_FOLDERS = ("internal", "detail")
ABOVE_EVAL_CORE = ["explain.h", "ablation.h", "internal/evaluation_json.h", "internal/rows_json.h",
                   "internal/explanation_json.h", "internal/ablation_json.h",
                   "internal/risk_coverage_json.h"]
SOURCE_SUFFIXES = (".h", ".cpp", ".in")
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.MULTILINE)
LMK_INCLUDE = re.compile(r"^lmk/([a-z0-9_]+)/(.*)$")


def read_tree(root):
    """{path relative to root: text} of every C++ source and header of the checked folders."""
    files = {}
    for top in list(LEVEL) + ABOVE_ALL:
        for folder, subfolders, names in os.walk(os.path.join(root, top)):
            subfolders[:] = [s for s in subfolders if not s.startswith(".")]
            for name in names:
                if name.endswith(SOURCE_SUFFIXES):
                    path = os.path.join(folder, name)
                    with open(path, encoding="utf-8", errors="replace") as f:
                        files[os.path.relpath(path, root)] = f.read()
    return files


def includes(files):
    """(file, its module, the included module, the rest of the include path) per lmk include."""
    for path, text in sorted(files.items()):
        module = path.split(os.sep)[0]
        for target in INCLUDE.findall(text):
            if target.startswith("../"):
                yield path, module, None, target
                continue
            match = LMK_INCLUDE.match(target)
            if match:
                yield path, module, match.group(1), match.group(2)


def violations(files):
    """One line per include against the layering rule."""
    found = []
    for path, module, included, rest in includes(files):
        if included is None:
            found.append(f"{path}: includes '{rest}' by a relative path out of its folder; "
                         f"include it as \"lmk/MODULE/...\"")
            continue
        folders = path.split(os.sep)[1:-1]
        installed_header = (module not in NOT_INSTALLED + ABOVE_ALL and path.endswith(".h")
                            and not any(f in PRIVATE_FOLDERS for f in folders))
        if installed_header and any(f in PRIVATE_FOLDERS for f in rest.split("/")[:-1]):
            found.append(f"{path}: an installed header includes lmk/{included}/{rest}, which is not "
                         f"installed; include it from a source file")
        if path.replace(os.sep, "/") in EVAL_CORE and included == "eval" and rest in ABOVE_EVAL_CORE:
            found.append(f"{path}: the evaluation's core includes lmk/eval/{rest}, a report built "
                         f"on it; share what both need from below (eval/internal/pair_result_json.h)")
        if module in ABOVE_ALL or included == module:
            continue
        if included not in LEVEL:
            found.append(f"{path}: includes lmk/{included}/{rest}, which is no module of lmk")
            continue
        if "detail" in rest.split("/")[:-1]:
            found.append(f"{path}: includes lmk/{included}/{rest}: a module's detail/ is its own; "
                         f"share it from {included}/ or {included}/internal/")
        if LEVEL[included] > LEVEL[module]:
            found.append(f"{path}: {module} includes lmk/{included}/{rest}, a layer above it "
                         f"({layer_order()})")
        elif LEVEL[included] == LEVEL[module]:
            found.append(f"{path}: {module} includes lmk/{included}/{rest}; {module} and "
                         f"{included} are one layer and do not include each other")
    return found


def include_links(root):
    """Problems with include/lmk/, which makes "lmk/MODULE/..." resolve from the source tree."""
    problems = []
    for module in LEVEL:
        if module in ("tools", "python"):
            continue
        link = os.path.join(root, "include", "lmk", module)
        if os.path.realpath(link) != os.path.realpath(os.path.join(root, module)):
            problems.append(f"include/lmk/{module}: should be a link to ../../{module}")
    return problems


def layer_order():
    return " < ".join(", ".join(layer) for layer in LAYERS)


def counts_table(files):
    """Markdown: for each module, how many of its includes go to each module below it."""
    counts = {}
    for _, module, included, _ in includes(files):
        if included is not None and module in LEVEL and included != module:
            counts[(module, included)] = counts.get((module, included), 0) + 1
    modules = [m for layer in LAYERS for m in layer]
    lines = ["| includer \\ included | " + " | ".join(modules[:-2]) + " |",
             "|---" * (len(modules) - 1) + "|"]
    for module in modules[1:]:
        cells = [str(counts.get((module, other), "")) for other in modules[:-2]]
        lines.append(f"| {module} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


# The counts table in a document lies between these lines, so that it is generated, not typed.
DOCS_BEGIN = "<!-- counts: generated by tests/layering/check_layering.py --write-docs -->"
DOCS_END = "<!-- end of counts -->"


def docs_block(text, path):
    """The start and end offsets of the table between the markers in `text`."""
    begin, end = text.find(DOCS_BEGIN), text.find(DOCS_END)
    if begin < 0 or end < begin:
        raise ValueError(f"{path}: no counts table between '{DOCS_BEGIN}' and '{DOCS_END}'")
    return begin + len(DOCS_BEGIN), end


def check_docs(files, path):
    """A line when `path`'s counts table differs from the tree's, else nothing."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    begin, end = docs_block(text, path)
    if text[begin:end].strip() != counts_table(files):
        return [f"{path}: the include counts table is not the tree's; regenerate it with "
                f"tests/layering/check_layering.py --write-docs {path}"]
    return []


def write_docs(files, path):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    begin, end = docs_block(text, path)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text[:begin] + "\n" + counts_table(files) + "\n" + text[end:])


def self_test(files):
    """Plants one violation of each kind into the real tree's files and checks that it is seen,
    and that the real tree's own verdict does not change otherwise."""
    plants = {
        "geometry/planted_upward.cpp": '#include "lmk/landmark/landmark.h"\n',
        "landmark/planted_detail.cpp": '#include "lmk/geometry/detail/pcd_io.h"\n',
        "ros/planted_same_layer.cpp": '#include "lmk/serve/http_server.h"\n',
        "tools/planted_relative.cpp": '#include "../eval/evaluation.h"\n',
        "json/planted_upward.h": '#include "lmk/pbd/plan.h"\n',
        "landmark/planted_public.h": '#include "lmk/landmark/internal/capture_findings_json.h"\n',
        "search/metrics/planted_public.h": '#include "lmk/search/internal/terms_json.h"\n',
        "search/planted_upward.cpp": '#include "lmk/sim/mesh.h"\n',
        "eval/planted_nested_detail.cpp": '#include "lmk/search/fast/detail/voting.h"\n',
        "eval/evaluation.cpp": '#include "lmk/eval/explain.h"\n',
        "eval/detail/pair_cache.cpp": '#include "lmk/eval/internal/evaluation_json.h"\n',
    }
    before = set(violations(files))
    failures = []
    for path, text in plants.items():
        after = set(violations({**files, path: text})) - before
        if not any(line.startswith(path + ":") for line in after):
            failures.append(f"self-test: the planted {path} ({text.strip()}) was not reported")
        # Allowed includes stay allowed: tests may look inside any module.
    allowed = {"tests/planted_white_box.cpp": '#include "lmk/geometry/detail/pcd_io.h"\n',
               "landmark/planted_below.cpp": '#include "lmk/occupancy/distance_field.h"\n',
               "landmark/planted_source.cpp":
                   '#include "lmk/landmark/internal/capture_findings_json.h"\n',
               "landmark/internal/planted.h": '#include "lmk/landmark/detail/landmark_record.h"\n',
               "search/fast/planted.cpp": '#include "lmk/search/detail/reference_search.h"\n',
               "sim/planted_below.cpp": '#include "lmk/search/find_landmark.h"\n'}
    for path, text in allowed.items():
        if set(violations({**files, path: text})) - before:
            failures.append(f"self-test: the allowed {path} ({text.strip()}) was reported")
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--root", default=os.path.join(os.path.dirname(__file__), "..", ".."),
                        help="the source tree (default: this file's)")
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument("--counts", action="store_true", help="print the include counts table")
    mode.add_argument("--self-test", action="store_true", help="plant violations, see them fail")
    mode.add_argument("--check-docs", metavar="FILE",
                      help="check FILE's counts table against the tree")
    mode.add_argument("--write-docs", metavar="FILE", help="write the tree's counts into FILE")
    args = parser.parse_args()
    files = read_tree(args.root)
    if not files:
        print(f"check_layering: no sources under {args.root}", file=sys.stderr)
        return 2
    if args.counts:
        print(counts_table(files))
        return 0
    try:
        if args.write_docs:
            write_docs(files, args.write_docs)
            return 0
        if args.check_docs:
            problems = check_docs(files, args.check_docs)
            for line in problems:
                print(line)
            if not problems:
                print(f"check_layering: {args.check_docs}'s counts table is the tree's")
            return 1 if problems else 0
    except (OSError, ValueError) as e:
        print(f"check_layering: {e}", file=sys.stderr)
        return 2
    problems = self_test(files) if args.self_test else violations(files) + include_links(args.root)
    for line in problems:
        print(line)
    if not problems:
        print(f"check_layering: {len(files)} files, "
              + ("every planted violation seen" if args.self_test else "no violation"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
