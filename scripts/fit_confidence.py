#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Fits lmk's confidence calibration (landmark/confidence_calibration.h) on labelled searches.

Each input is the JSON of `lmk eval --json FILE` (any dataset: a preset, an imported RGB-D
sequence). Every match below the evaluation's threshold in an in-context pair is a sample: its
features (found[].confidence.features, as the search computes them) and whether the protocol
counted it right (found[].correct). A logistic model, with a small ridge so that a feature the data
cannot fix stays near 0, is fitted by Newton's method, and written as the versioned calibration
file the search reads:

  scripts/fit_confidence.py --fit paper.json desk.json --check kitchen.json \\
      -o landmark/data/confidence_calibration.json

`--check` files are not fitted on: their expected calibration error and precision at the cuts are
printed beside the fitted ones (tune on one real sequence, report on the other). `--features`
limits the model to some features. `--dump FILE` writes the samples as CSV (the fit's data, kept
in docs/confidence/ with the figures).
"""

import argparse
import csv
import json
import math
import sys

import numpy as np

FORMAT = "lmk-confidence-calibration"
VERSION = 1


def samples(path):
    """(features dict, right, range, best) for each match below the threshold, in-context pairs."""
    with open(path) as f:
        e = json.load(f)
    out = []
    for pair in e["pairs"]:
        if not pair["in_context"]:
            continue
        best = True
        for m in pair["found"]:
            if not m["within_threshold"]:
                continue
            c = m["confidence"]
            out.append((c["features"], bool(m["correct"]), c["range"], best, path))
            best = False
    return e.get("metric"), out


def design(rows, names):
    return np.array([[1.0] + [r[0][n] for n in names] for r in rows])


def fit(x, y, ridge):
    """Logistic regression by Newton's method, ridge on every weight but the bias."""
    w = np.zeros(x.shape[1])
    penalty = np.full(x.shape[1], ridge)
    penalty[0] = 0.0
    for _ in range(100):
        p = 1.0 / (1.0 + np.exp(-x @ w))
        gradient = x.T @ (p - y) + penalty * w
        hessian = (x * (p * (1 - p))[:, None]).T @ x + np.diag(penalty) + 1e-9 * np.eye(len(w))
        step = np.linalg.solve(hessian, gradient)
        w -= step
        if np.max(np.abs(step)) < 1e-10:
            break
    return w


def ece(p, y, bins=10):
    total = 0.0
    for b in range(bins):
        lo, hi = b / bins, (b + 1) / bins
        inside = (p >= lo) & ((p < hi) if b < bins - 1 else (p <= hi))
        if inside.any():
            total += inside.sum() / len(p) * abs(p[inside].mean() - y[inside].mean())
    return total


def report(label, rows, names, w):
    if not rows:
        return
    x, y = design(rows, names), np.array([r[1] for r in rows], dtype=float)
    p = 1.0 / (1.0 + np.exp(-x @ w))
    best = np.array([r[3] for r in rows])
    line = f"{label}: {len(rows)} matches, {int(y.sum())} right, ECE {ece(p, y):.3f}"
    pb, yb = p[best], y[best]
    for cut in (0.5, 0.8, 0.9, 0.95):
        answered = pb >= cut
        precision = yb[answered].mean() if answered.any() else float("nan")
        line += f"; best >= {cut}: {int(answered.sum())}/{len(pb)} at {precision:.3f}"
    print(line)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--fit", nargs="+", required=True, help="lmk eval --json files to fit on")
    parser.add_argument("--check", nargs="*", default=[], help="files to report on, not fit on")
    parser.add_argument("--features", nargs="*", help="features to weigh (default: all)")
    parser.add_argument("--ridge", type=float, default=1.0, help="ridge on the weights")
    parser.add_argument("--note", default="", help="what it was fitted on, for the file")
    parser.add_argument("-o", "--output", help="the calibration file to write")
    parser.add_argument("--dump", help="write the fitted samples as CSV")
    a = parser.parse_args()

    metric, rows = None, []
    for path in a.fit:
        m, s = samples(path)
        if metric and m != metric:
            sys.exit(f"fit_confidence: {path} was evaluated with metric {m}, the others with {metric}")
        metric = m
        rows += s
    if not rows:
        sys.exit("fit_confidence: no in-context match below the threshold in the --fit files")
    names = a.features or list(rows[0][0].keys())
    x, y = design(rows, names), np.array([r[1] for r in rows], dtype=float)
    w = fit(x, y, a.ridge)
    print("weights: bias %.4f, " % w[0] + ", ".join(f"{n} {v:.4f}" for n, v in zip(names, w[1:])))
    for path in a.fit:
        report(f"fit   {path}", [r for r in rows if r[4] == path], names, w)
    for path in a.check:
        report(f"check {path}", samples(path)[1], names, w)
    if a.dump:
        with open(a.dump, "w", newline="") as f:
            out = csv.writer(f)
            out.writerow(["file", "right", "best", "range"] + names)
            for r in rows:
                out.writerow([r[4], int(r[1]), int(r[3]), r[2]] + [r[0][n] for n in names])
    if a.output:
        calibration = {
            "format": FORMAT,
            "version": VERSION,
            "metric": metric,
            "fitted_on": a.note or ", ".join(a.fit),
            "bias": float(w[0]),
            "weights": {n: float(v) for n, v in zip(names, w[1:])},
        }
        with open(a.output, "w") as f:
            json.dump(calibration, f, indent=2)
            f.write("\n")


if __name__ == "__main__":
    main()
