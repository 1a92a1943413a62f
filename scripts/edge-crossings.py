#!/usr/bin/env python3
"""Counts the collision edges of a scene that cut through a capsule or a disc.

    python3 scripts/edge-crossings.py SCENE.json TRAJECTORY.csv

SCENE.json is a scene file with a capsule or disc collider and collisionEdges;
TRAJECTORY.csv is what `particle-lab run --scene-file SCENE.json --trajectory
TRAJECTORY.csv` wrote (every step). Between two recorded steps the edge's ends
are moved in a straight line over 32 sub-steps; an edge cuts through when one
of 19 points spread along the capsule's core changes side of it while lying
over the edge's interior at both sub-steps (for a disc: its centre). The
first capsule or disc of the scene is judged. Prints the count and the steps of
the first cuts. A step's motion that is not straight between records is
approximated, so record every step (--every 1, the default).
"""
import collections
import csv
import json
import sys


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: edge-crossings.py SCENE.json TRAJECTORY.csv")
    scene = json.load(open(sys.argv[1]))
    cores = [c for c in scene.get("colliders", []) if c.get("type") in ("capsule", "disc")]
    if not cores:
        sys.exit("edge-crossings: the scene has no capsule or disc")
    if cores[0]["type"] == "disc":
        core = [tuple(cores[0]["centre"])]
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
        ex, ey = q[0] - p[0], q[1] - p[1]
        length2 = ex * ex + ey * ey
        out = []
        for c in core:
            cx, cy = c[0] - p[0], c[1] - p[1]
            out.append(((cx * ex + cy * ey) / length2 if length2 > 0 else -1.0, ex * cy - ey * cx))
        return out

    lerp = lambda p, q, u: (p[0] + u * (q[0] - p[0]), p[1] + u * (q[1] - p[1]))
    inside = lambda s: 0 < s[0] < 1
    cut = {}
    previous = None
    for step, x in steps.items():
        if previous is not None:
            for k, (i, j) in enumerate(edges):
                if k in cut:
                    continue
                before = None
                for m in range(33):
                    u = m / 32
                    now = sides(lerp(previous[i], x[i], u), lerp(previous[j], x[j], u))
                    if before and any(inside(s0) and inside(s1) and s0[1] * s1[1] < 0 for s0, s1 in zip(before, now)):
                        cut[k] = step
                        break
                    before = now
        previous = x
    print("%d of %d edges cut through the %s; first at steps %s" % (len(cut), len(edges), cores[0]["type"], sorted(cut.values())[:8]))


if __name__ == "__main__":
    main()
