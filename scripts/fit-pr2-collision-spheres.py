#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Fits the collision spheres of lmk's PR2 description (pr2/data/pr2.urdf, issue #60).

Reads the full PR2 description's collision meshes (STL), link by link in lmk's link frames (the
fingers, which lmk's model does not move, closed on the palm), and writes for each link a few dozen
spheres inside the mesh whose union reaches every point of its surface within a tolerance:

1. points spread over the mesh's triangles, each with its triangle's outward normal;
2. at each point the largest ball inside the mesh that touches it there (the shrinking-ball
   estimate of the medial axis: shrink a ball tangent at the point until no other surface point
   lies inside it);
3. a greedy cover: the ball that brings the most uncovered surface points within the tolerance of
   its own surface, until every point is covered.

Spheres inside the surface never reach beyond it; between them the union falls short of the
surface by at most the tolerance. The output replaces the <collision> elements of the links in
pr2/data/pr2.urdf (--write) or is printed. Needs numpy and scipy (python3-numpy, python3-scipy).

    scripts/fit-pr2-collision-spheres.py ../shared/data/robots/pr2/robot.urdf --write
"""

import argparse
import math
import re
import struct
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
from scipy.spatial import ConvexHull, cKDTree

# lmk's links and, for each, the full description's links whose meshes it carries (fixed to it in
# lmk's model), with the joint values they are fitted at.
ARM_LINKS = ["shoulder_pan_link", "shoulder_lift_link", "upper_arm_roll_link", "upper_arm_link",
             "elbow_flex_link", "forearm_roll_link", "forearm_link", "wrist_flex_link",
             "wrist_roll_link", "gripper_palm_link"]
FINGERS = ["gripper_l_finger_link", "gripper_r_finger_link", "gripper_l_finger_tip_link",
           "gripper_r_finger_tip_link"]


def rpy_matrix(r, p, y):
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def origin_of(element):
    T = np.eye(4)
    o = element.find("origin") if element is not None else None
    if o is not None:
        T[:3, 3] = [float(v) for v in o.get("xyz", "0 0 0").split()]
        T[:3, :3] = rpy_matrix(*[float(v) for v in o.get("rpy", "0 0 0").split()])
    return T


def read_stl(path):
    data = path.read_bytes()
    n = struct.unpack("<I", data[80:84])[0]
    if 84 + 50 * n != len(data):
        raise SystemExit(f"{path}: only binary STL is read here")
    rec = np.frombuffer(data[84:], dtype=np.dtype([("n", "<3f4"), ("v", "<9f4"), ("a", "<u2")]), count=n)
    return rec["v"].reshape(-1, 3, 3).astype(float)


def link_triangles(robot, root, link_name, T_link):
    """The link's collision mesh triangles, moved by T_link (into the lmk link's frame)."""
    link = robot.find(f"link[@name='{link_name}']")
    out = []
    for c in link.findall("collision"):
        mesh = c.find("geometry/mesh")
        if mesh is None:
            continue
        rel = re.sub(r"^package://[^/]+/", "", mesh.get("filename"))
        tris = read_stl(root / rel)
        # Outward normals need counter-clockwise triangles seen from outside: a closed mesh wound
        # the other way has a negative volume, and is turned over.
        volume = np.einsum("ij,ij->i", tris[:, 0], np.cross(tris[:, 1], tris[:, 2])).sum() / 6.0
        if volume < 0:
            tris = tris[:, ::-1]
        scale = np.array([float(v) for v in mesh.get("scale", "1 1 1").split()])
        T = T_link @ origin_of(c)
        pts = tris.reshape(-1, 3) * scale
        out.append((pts @ T[:3, :3].T + T[:3, 3]).reshape(-1, 3, 3))
    return out


def finger_transform(robot, finger):
    """A finger link's pose in the palm's frame at joint value 0 (closed)."""
    T = np.eye(4)
    name = finger
    while True:
        joint = next(j for j in robot.findall("joint") if j.find("child").get("link") == name)
        T = origin_of(joint) @ T
        name = joint.find("parent").get("link")
        if name.endswith("gripper_palm_link"):
            return T


def surface_samples(tris, count, rng):
    """Points spread over the triangles by area, with their triangles' outward unit normals."""
    a, b, c = tris[:, 0], tris[:, 1], tris[:, 2]
    cross = np.cross(b - a, c - a)
    area = 0.5 * np.linalg.norm(cross, axis=1)
    keep = area > 1e-12
    tris, cross, area = tris[keep], cross[keep], area[keep]
    pick = rng.choice(len(tris), count, p=area / area.sum())
    u = rng.random((count, 2))
    flip = u.sum(axis=1) > 1
    u[flip] = 1 - u[flip]
    t = tris[pick]
    points = t[:, 0] + u[:, :1] * (t[:, 1] - t[:, 0]) + u[:, 1:] * (t[:, 2] - t[:, 0])
    normals = cross[pick] / np.linalg.norm(cross[pick], axis=1, keepdims=True)
    return points, normals


def shrinking_balls(points, normals, candidates, r_max, tree):
    """At each point, the largest ball inside the surface that touches it there: a ball tangent at
    the point, shrunk until the surface point nearest its centre no longer lies inside it."""
    radius = np.full(len(candidates), r_max)
    for k, i in enumerate(candidates):
        p, n, r = points[i], -normals[i], r_max
        for _ in range(60):
            d, j = tree.query(p + r * n)
            if j == i or d >= r - 1e-6:
                break
            q = points[j]
            along = np.dot(q - p, n)
            if along <= 1e-9:
                break
            # The ball tangent at p through q: |p + r n - q| = r.
            r_new = np.dot(q - p, q - p) / (2.0 * along)
            if r_new >= r:
                break
            r = r_new
        radius[k] = r
    return points[candidates] - radius[:, None] * normals[candidates], radius


def greedy_cover(centres, radii, points, tolerance, coverage):
    """Spheres, most covering first, until `coverage` of the points lie within `tolerance` of one's
    surface (the rest: slivers and edges a sphere inside cannot reach)."""
    uncovered = np.ones(len(points), dtype=bool)
    chosen = []
    # Which candidate covers which point, computed once (bounded by the candidates' reach).
    tree = cKDTree(points)
    covers = [np.array(tree.query_ball_point(c, r + tolerance), dtype=int) for c, r in zip(centres, radii)]
    while uncovered.sum() > (1.0 - coverage) * len(points):
        gains = np.array([uncovered[cv].sum() if len(cv) else 0 for cv in covers])
        k = int(gains.argmax())
        if gains[k] == 0:
            break
        chosen.append(k)
        uncovered[covers[k]] = False
    return chosen


def hull_triangles(points):
    """The convex hull of `points`, as triangles wound outward."""
    hull = ConvexHull(points)
    out = points[hull.simplices]
    normal = np.cross(out[:, 1] - out[:, 0], out[:, 2] - out[:, 0])
    inward = np.einsum("ij,ij->i", normal, hull.equations[:, :3]) < 0
    out[inward] = out[inward][:, ::-1]
    return out


def slab_hulls(tris, slab, rng):
    """The mesh cut into slabs across its longest extent, each slab's convex hull. A collision mesh
    need not be closed, and what an arm touches a table or a box with is its outer surface: hulls
    make the fit robust to a mesh's holes and inner faces, and slabs keep a dip along the link (the
    forearm's waist) that one hull would fill."""
    points, _ = surface_samples(tris, 40000, rng)
    points = np.concatenate([points, tris.reshape(-1, 3)])
    axis = int(np.argmax(points.max(axis=0) - points.min(axis=0)))
    lo, hi = points[:, axis].min(), points[:, axis].max()
    count = max(1, int(math.ceil((hi - lo) / slab)))
    edges = np.linspace(lo, hi, count + 1)
    hulls = []
    for k, (a, b) in enumerate(zip(edges[:-1], edges[1:])):
        # Each slab overlaps its neighbours a little, so that their hulls meet.
        inside = points[(points[:, axis] >= a - 0.002) & (points[:, axis] <= b + 0.002)]
        if len(inside) >= 4:
            try:
                # The cuts between slabs lie inside the link: nothing there to cover.
                cuts = [c for c, inner in ((a - 0.002, k > 0), (b + 0.002, k < count - 1)) if inner]
                hulls.append((hull_triangles(inside), axis, cuts))
            except Exception:  # a flat slab has no volume: its points are covered by the next
                continue
    return hulls


def outer_samples(tris, axis, cuts, rng):
    """Points over a slab's hull with outward normals, but for those on its cuts."""
    points, normals = surface_samples(tris, 4000, rng)
    outer = np.ones(len(points), dtype=bool)
    for cut in cuts:
        outer &= ~((np.abs(points[:, axis] - cut) < 0.003) & (np.abs(normals[:, axis]) > 0.9))
    return points[outer], normals[outer]


def fit_link(tris_list, tolerance, coverage, min_radius, slab, rng):
    """Balls inside the slabs' outer surface, shrunk against all of it (a ball may span slabs),
    then the greedy cover of that surface."""
    samples = [outer_samples(h, axis, cuts, rng)
               for h, axis, cuts in slab_hulls(np.concatenate(tris_list), slab, rng)]
    points = np.concatenate([p for p, _ in samples])
    normals = np.concatenate([n for _, n in samples])
    tree = cKDTree(points)
    extent = np.linalg.norm(points.max(axis=0) - points.min(axis=0))
    candidates = rng.choice(len(points), min(3000, len(points)), replace=False)
    centres, radii = shrinking_balls(points, normals, candidates, 0.5 * extent, tree)
    ok = radii >= min_radius
    centres, radii = centres[ok], radii[ok]
    chosen = greedy_cover(centres, radii, points, tolerance, coverage)
    return centres[chosen], radii[chosen]


def collision_xml(centres, radii):
    lines = []
    for c, r in zip(centres, radii):
        lines.append(f'    <collision>\n      <origin xyz="{c[0]:.4f} {c[1]:.4f} {c[2]:.4f}" rpy="0 0 0"/>\n'
                     f'      <geometry><sphere radius="{r:.4f}"/></geometry>\n    </collision>')
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("urdf", type=Path, help="the full PR2 description (robot.urdf)")
    parser.add_argument("--tolerance", type=float, default=0.003, help="m (default 0.003)")
    parser.add_argument("--coverage", type=float, default=0.995,
                        help="the fraction of surface points covered (default 0.995)")
    parser.add_argument("--min-radius", type=float, default=0.005, help="m (default 0.005)")
    parser.add_argument("--grow", type=float, default=None,
                        help="m added to every radius (default: the tolerance), so that the union "
                             "reaches the hull's surface where the spheres inside fell short")
    parser.add_argument("--slab", type=float, default=0.06,
                        help="m: each link's mesh is fitted as convex slabs this thick (default 0.06)")
    parser.add_argument("--write", action="store_true", help="rewrite pr2/data/pr2.urdf")
    args = parser.parse_args()
    robot = ET.parse(args.urdf).getroot()
    root = args.urdf.parent
    rng = np.random.default_rng(59)
    spheres = {}
    names = [f"{s}_{l}" for s in "rl" for l in ARM_LINKS]
    for name in names:
        tris = link_triangles(robot, root, name, np.eye(4))
        if name.endswith("gripper_palm_link"):
            side = name[0]
            for finger in FINGERS:
                tris += link_triangles(robot, root, f"{side}_{finger}", finger_transform(robot, f"{side}_{finger}"))
        centres, radii = fit_link(tris, args.tolerance, args.coverage, args.min_radius, args.slab,
                                  rng)
        radii = radii + (args.tolerance if args.grow is None else args.grow)
        spheres[name] = (centres, radii)
        print(f"{name}: {len(radii)} spheres", file=sys.stderr)
    if not args.write:
        for name, (c, r) in spheres.items():
            print(f"<!-- {name} -->\n{collision_xml(c, r)}")
        return
    target = Path(__file__).resolve().parent.parent / "pr2" / "data" / "pr2.urdf"
    text = target.read_text()
    for name, (c, r) in spheres.items():
        pattern = re.compile(rf'<link name="{name}"(?:/>|>.*?</link>)', re.S)
        text, count = pattern.subn(f'<link name="{name}">\n{collision_xml(c, r)}\n  </link>', text)
        if count != 1:
            raise SystemExit(f"{target}: link {name} not found once")
    target.write_text(text)
    print(f"wrote {target}", file=sys.stderr)


if __name__ == "__main__":
    main()
