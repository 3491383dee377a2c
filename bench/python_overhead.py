#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The Python layer's overhead on one lmk.find of the real milk frame (issue #36): the call's wall
time against the C++ search's own time (its stats' seconds), median of 30 runs on one thread.

    PYTHONPATH=build/python python3 bench/python_overhead.py ../shared/data

The landmark is the milk carton of pcl/milk.pcd's crop, with 2 cm of free space on the sides that
face it (left, right, top, front), as lmk bench's built-in workload draws it."""
import statistics
import sys
import time

import numpy as np

import lmk

data = sys.argv[1]
scene = lmk.read_cloud(data + "/pcl/milk_cartoon_all_small_clorox.pcd")
crop = lmk.read_cloud(data + "/pcl/milk.pcd").points.reshape(-1, 3)
crop = crop[np.isfinite(crop).all(axis=1)]
lo, hi = crop.min(axis=0).astype(float), crop.max(axis=0).astype(float)
# 2 cm on the sides facing free space: left/right (x), top (-y), front (-z)
lo[0] -= 0.02; hi[0] += 0.02; lo[1] -= 0.02; lo[2] -= 0.02
pose = np.eye(4); pose[:3, 3] = (lo + hi) / 2
landmark, _ = lmk.capture(scene, pose, hi - lo, name="milk", check=False)
ratios = []
for _ in range(30):
    t = time.perf_counter(); r = lmk.find(scene, landmark, threads=1); wall = time.perf_counter() - t
    ratios.append(wall / r["stats"]["seconds"])
print(f"{len(r['matches'])} match(es); search {r['stats']['seconds']:.4f} s; "
      f"lmk.find / C++ search: {statistics.median(ratios):.3f} (median of {len(ratios)})")
