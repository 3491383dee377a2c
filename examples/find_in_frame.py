#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Loads a frame, captures a landmark in it with a box, finds the landmark and prints the matches.

    python3 examples/find_in_frame.py SCENE.pcd CX CY CZ SX SY SZ [NAME]

The box is axis-aligned in the scene's frame: its centre and its sides, in metres. Run with
PYTHONPATH=build/python from a build tree (docs/python.md)."""

import sys

import numpy as np

import lmk


def main(argv):
    if len(argv) not in (8, 9):
        sys.exit(__doc__)
    scene = lmk.read_cloud(argv[1])
    centre, size = [float(v) for v in argv[2:5]], [float(v) for v in argv[5:8]]
    box_pose = np.eye(4)
    box_pose[:3, 3] = centre
    landmark, verdict = lmk.capture(scene, box_pose, size, name=argv[8] if len(argv) == 9 else "box")
    print(f"captured '{landmark.name}': {len(landmark.points)} points; "
          f"distinctive: {verdict['distinctive']}")
    for line in verdict["slides"]:
        print(f"  {line}")
    result = lmk.find(scene, landmark)
    print(f"{len(result['matches'])} match(es): {result['stats']['rejections'] or 'none rejected'}")
    for rank, match in enumerate(result["matches"], 1):
        x, y, z = match["position"]
        print(f"  {rank}: at {x:.3f} {y:.3f} {z:.3f} m, error {1000 * match['error']:.1f} mm")


if __name__ == "__main__":
    main(sys.argv)
