#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Ablates the error metrics over thresholds on the `paper` preset with lmk.ablate, and draws
precision against recall, one line per metric, into a PNG.

    python3 examples/ablate_metrics.py OUT.png [--types TYPE,...] [--cache DIR]

Every variant is an ordinary evaluation in lmk's cache, shared with `lmk eval` and `lmk ablate`.
Run with PYTHONPATH=build/python from a build tree (docs/python.md)."""

import argparse

import matplotlib

matplotlib.use("Agg")  # a file, no display
import matplotlib.pyplot as plt  # noqa: E402

import lmk  # noqa: E402

METRICS = ["paper", "vdb", "visibility"]
THRESHOLDS = [0.003, 0.0045, 0.006, 0.008]  # m


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--types", default="", help="only these scene types, comma-separated")
    parser.add_argument("--cache", default=None, help="lmk's cache (default: lmk's own)")
    args = parser.parse_args()
    types = [t for t in args.types.split(",") if t]
    result = lmk.ablate({"metric": METRICS, "threshold": THRESHOLDS}, preset="paper",
                        types=types, cache=args.cache, in_context=True)
    figure, axes = plt.subplots(figsize=(5, 4))
    for metric in METRICS:
        points = []
        for variant in result["variants"]:
            if variant["values"]["metric"] != metric:
                continue
            row = next(r for r in variant["rows"] if r["setting"] == "all" and r["assumption"] == 2)
            points.append((row["recall"] or 0.0, row["precision"] or 0.0))
        points.sort()
        axes.plot([r for r, _ in points], [p for _, p in points], marker="o", label=metric)
    axes.set_xlabel("recall (in context)")
    axes.set_ylabel("precision (in context)")
    axes.set_xlim(0, 1.02)
    axes.set_ylim(0, 1.02)
    axes.set_title(f"lmk {lmk.__version__}: metrics over thresholds {THRESHOLDS} m")
    axes.legend()
    figure.tight_layout()
    figure.savefig(args.out, dpi=100)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
