#!/usr/bin/env python3
"""Counts the collision edges of a scene that cut through a capsule or a disc, or pass a
corner of a box or polygon.

    python3 scripts/edge-crossings.py SCENE.json TRAJECTORY.csv

SCENE.json is a scene file with a capsule, disc, box or polygon collider and collisionEdges;
TRAJECTORY.csv is what `particle-lab run --scene-file SCENE.json --trajectory
TRAJECTORY.csv` wrote (every step). Between two recorded steps the edge's ends
are moved in a straight line over 32 sub-steps; an edge cuts through when one
of 19 points spread along the capsule's core changes side of it while lying
over the edge's interior (for a disc: its centre; for a box or polygon: its
corners); a point within the contact slop (1e-9 m) of the edge touches it and
keeps the side it came from, so an edge that stops on a corner and then
passes it counts. The first capsule, disc, box or polygon of the scene is
judged. Prints the count and the steps of the first cuts. A step's motion
that is not straight between records is approximated, so record every step
(--every 1, the default).
"""
import collections
import csv
import json
import math
import sys

SLOP = 1e-9  # m: the contact slop (FORMAT.md); a point this near the edge touches it


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: edge-crossings.py SCENE.json TRAJECTORY.csv")
    scene = json.load(open(sys.argv[1]))
    cores = [c for c in scene.get("colliders", []) if c.get("type") in ("capsule", "disc", "box", "polygon")]
    if not cores:
        sys.exit("edge-crossings: the scene has no capsule, disc, box or polygon")
    if cores[0]["type"] == "disc":
        core = [tuple(cores[0]["centre"])]
    elif cores[0]["type"] == "box":
        (x0, y0), (x1, y1) = cores[0]["min"], cores[0]["max"]
        core = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    elif cores[0]["type"] == "polygon":
        core = [tuple(v) for v in cores[0]["vertices"]]
    else:
        a, b = cores[0]["from"], cores[0]["to"]
        core = [(a[0] + (b[0] - a[0]) * k / 20, a[1] + (b[1] - a[1]) * k / 20) for k in range(1, 20)]
    edges = [(e[0], e[1]) for e in scene.get("collisionEdges", [])]
    steps = collections.OrderedDict()
    with open(sys.argv[2]) as f:
        rows = csv.reader(f)
        next(rows)
        for row in rows:
            steps.setdefault(int(row[0]), {})[int(row[2])] = (float(row[3]), float(row[4]))

    def sides(p, q):
        """Per core point: its projection's fraction along p→q and its side of the line (signed
        distance, 0 within the contact slop, so that a point resting on the edge has no side)."""
        ex, ey = q[0] - p[0], q[1] - p[1]
        length2 = ex * ex + ey * ey
        out = []
        for c in core:
            cx, cy = c[0] - p[0], c[1] - p[1]
            distance = (ex * cy - ey * cx) / math.sqrt(length2) if length2 > 0 else 0.0
            out.append(((cx * ex + cy * ey) / length2 if length2 > 0 else -1.0,
                        0 if abs(distance) <= SLOP else math.copysign(1, distance)))
        return out

    lerp = lambda p, q, u: (p[0] + u * (q[0] - p[0]), p[1] + u * (q[1] - p[1]))
    inside = lambda s: 0 < s[0] < 1
    cut = {}
    # The side each core point was last seen on while over the edge's interior
    # (None once it is not over it): a point that touches the edge keeps the
    # side it came from, so passing through a touch counts.
    last = {k: [None] * len(core) for k in range(len(edges))}
    previous = None
    for step, x in steps.items():
        if previous is not None:
            for k, (i, j) in enumerate(edges):
                for m in range(1, 33) if k not in cut else ():
                    u = m / 32
                    for c, s in enumerate(sides(lerp(previous[i], x[i], u), lerp(previous[j], x[j], u))):
                        if not inside(s):
                            last[k][c] = None
                        elif s[1] != 0:
                            if last[k][c] is not None and last[k][c] != s[1]:
                                cut[k] = step
                            last[k][c] = s[1]
                    if k in cut:
                        break
        else:
            for k, (i, j) in enumerate(edges):
                last[k] = [s[1] if inside(s) and s[1] != 0 else None for s in sides(x[i], x[j])]
        previous = x
    what = "passed a corner of the" if cores[0]["type"] in ("box", "polygon") else "cut through the"
    print("%d of %d edges %s %s; first at steps %s" % (len(cut), len(edges), what, cores[0]["type"], sorted(cut.values())[:8]))


if __name__ == "__main__":
    main()
