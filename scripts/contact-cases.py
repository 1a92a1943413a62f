#!/usr/bin/env python3
"""Runs the contact cases (constrained particles meeting colliders, dopri5 across
contacts, static friction, cloth against a thin capsule, seams, the wedge
billiard) through `particle-lab run` under every integrator and prints one
Markdown table per case with what each run measured.

    python3 scripts/contact-cases.py [--lab build/demos/particle-lab] [--jobs N] [CASE ...]

CASE is any of the names below (default: all). The scene files are
tests/data/contacts/*.json, or built here from their description; every run is
`particle-lab run --scene-file F --integrator I --dt DT --steps N` with --csv
(and --trajectory where positions are judged). Exit codes: 3 is a divergence
(energy blow-up, non-finite state or a failed step), which the tables show.
"""
import argparse
import concurrent.futures
import csv
import io
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests", "data", "contacts")
INTEGRATORS = ["euler", "symplectic-euler", "midpoint", "rk4", "verlet", "rattle", "implicit-euler", "xpbd", "dopri5"]
G = 9.81


def load(name):
    with open(os.path.join(DATA, name)) as f:
        return json.load(f)


class Runner:
    def __init__(self, lab, work, jobs):
        self.lab, self.work, self.jobs, self.count = lab, work, jobs, 0

    def scene(self, scene):
        self.count += 1
        path = os.path.join(self.work, "scene%d.json" % self.count)
        with open(path, "w") as f:
            json.dump(scene, f)
        return path

    def run(self, scene_path, integrator, dt, steps, trajectory=False):
        """(exit code, csv rows as dicts of floats, trajectory {step: {particle: (x, y)}})"""
        tag = "%s-%s-%g-%d" % (os.path.basename(scene_path), integrator, dt, steps)
        out_csv = os.path.join(self.work, tag + ".csv")
        out_traj = os.path.join(self.work, tag + ".traj.csv")
        command = [self.lab, "run", "--scene-file", scene_path, "--integrator", integrator, "--dt", repr(dt),
                   "--steps", str(steps), "--csv", out_csv, "--threads", "1"]
        if trajectory:
            command += ["--trajectory", out_traj]
        done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        rows = []
        if os.path.exists(out_csv):
            with open(out_csv) as f:
                rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
            os.remove(out_csv)
        positions = {}
        if trajectory and os.path.exists(out_traj):
            with open(out_traj) as f:
                for r in csv.DictReader(f):
                    positions.setdefault(int(r["step"]), {})[int(r["particle"])] = (float(r["x"]), float(r["y"]))
            os.remove(out_traj)
        return done.returncode, rows, positions

    def many(self, jobs):
        """Runs (key, scene_path, integrator, dt, steps, trajectory) tuples in parallel: {key: result}."""
        with concurrent.futures.ThreadPoolExecutor(self.jobs) as pool:
            futures = {key: pool.submit(self.run, *args) for key, *args in jobs}
            return {key: f.result() for key, f in futures.items()}


def energy_rise(rows):
    return max(r["total_energy"] for r in rows) - rows[0]["total_energy"] if rows else float("nan")


def table(title, header, lines):
    print("\n### %s\n" % title)
    print("| " + " | ".join(header) + " |")
    print("|" + " --- |" * len(header))
    for line in lines:
        print("| " + " | ".join(str(x) for x in line) + " |")


def g(x, digits=3):
    return "%.*g" % (digits, x) if isinstance(x, float) and math.isfinite(x) else str(x)


def chain_on_floor(r):
    """Pinned 12-rod chain (10 cm rods) released level, falling onto a floor 0.5 m below its pin; 5 s."""
    lines = []
    for e, mu in [(0.0, 0.0), (0.5, 0.3)]:
        scene = load("chain-lands-on-floor.json")
        scene["colliders"][0].update(restitution=e, friction=mu)
        path = r.scene(scene)
        results = r.many([(i, path, i, 0.002, 2500, False) for i in INTEGRATORS])
        for i in INTEGRATORS:
            rc, rows, _ = results[i]
            worst = max(x["max_constraint_error"] for x in rows) / 0.1
            lines.append((e, mu, i, rc, "%.2f %%" % (100 * worst), g(energy_rise(rows))))
    table("Pinned 12-rod chain lands on a floor 0.5 m below its pin (dt 0.002 s, 5 s)",
          ["e", "μ", "integrator", "exit", "max \\|C\\|/L", "max energy rise (J)"], lines)


def chain_on_slope(r):
    """Free 12-particle chain dropped 0.3 m onto a 20° slope with μ 0.5; 5 s."""
    path = r.scene(load("chain-dropped-on-slope.json"))
    runs = [((i, 0.002), path, i, 0.002, 2500, False) for i in INTEGRATORS]
    runs += [(("rk4", dt), path, "rk4", dt, int(round(5.0 / dt)), False) for dt in (0.0005, 0.0001)]
    results = r.many(runs)
    lines = []
    for (i, dt), (rc, rows, _) in results.items():
        lines.append((i, dt, rc, g(rows[-1]["kinetic"]), g(energy_rise(rows)),
                      "%.2f %%" % (100 * max(x["max_constraint_error"] for x in rows) / 0.1)))
    table("Free 12-particle chain dropped onto a 20° slope (μ 0.5), 5 s",
          ["integrator", "dt (s)", "exit", "final kinetic (J)", "max energy rise (J)", "max \\|C\\|/L"], lines)


def wire_and_floor(r):
    """A 1 kg bead on a 0.5 m wire: a floor cutting the wire 2 cm above its bottom, and one tangent to it."""
    lines = []
    cut = r.scene(load("wire-cut-by-floor.json"))
    tangent = load("wire-tangent-to-floor.json")
    free = dict(tangent, colliders=[])
    runs = []
    for i in INTEGRATORS:
        runs += [(("cut", i, 0.005), cut, i, 0.005, 2000, False)]
        runs += [(("tangent", i, 0.005), r.scene(tangent), i, 0.005, 2000, False)]
        runs += [(("no floor", i, 0.005), r.scene(free), i, 0.005, 2000, False)]
    runs += [(("tangent", "midpoint", 0.001), r.scene(tangent), "midpoint", 0.001, 10000, False),
             (("no floor", "midpoint", 0.001), r.scene(free), "midpoint", 0.001, 10000, False)]
    results = r.many(runs)
    for (floor, i, dt), (rc, rows, _) in results.items():
        lines.append((floor, i, dt, rc, g(rows[-1]["total_energy"] - rows[0]["total_energy"], 5), g(rows[-1]["kinetic"]),
                      g(max(x["max_constraint_error"] for x in rows))))
    table("Bead on a 0.5 m wire, 10 s: the floor cuts its bottom (ΔE should be −g·0.23 = −2.256 J, at rest), "
          "is tangent to it, or is absent",
          ["floor", "integrator", "dt (s)", "exit", "ΔE at 10 s (J)", "final kinetic (J)", "max \\|C\\| (m)"], lines)


def slope(angle_degrees, mu, e=0.5):
    a = math.radians(angle_degrees)
    normal, along = [-math.sin(a), math.cos(a)], [math.cos(a), math.sin(a)]
    return {"name": "slope", "integrator": "rk4", "dt": 0.01,
            "particles": [{"position": [2 * along[0], 2 * along[1]], "mass": 1}],
            "forces": [{"type": "gravity", "acceleration": [0, -G]}],
            "colliders": [{"type": "halfPlane", "point": [0, 0], "normal": normal, "restitution": e, "friction": mu}]}, along


def friction(r):
    """A particle at rest on a slope with μ 0.5: 20° (below the friction angle 26.6°) holds, 35° slides."""
    lines = []
    runs = []
    for angle in (20.0, 35.0):
        scene, along = slope(angle, 0.5)
        path = r.scene(scene)
        for i in INTEGRATORS:
            for dt, steps in ((0.01, 1000 if angle == 20.0 else 200), (0.001, 10000 if angle == 20.0 else 2000)):
                runs.append(((angle, i, dt), path, i, dt, steps, True))
    results = r.many(runs)
    for (angle, i, dt), (rc, rows, positions) in results.items():
        a = math.radians(angle)
        along = (math.cos(a), math.sin(a))
        first, last = positions[min(positions)][0], positions[max(positions)][0]
        moved = (first[0] - last[0]) * along[0] + (first[1] - last[1]) * along[1]
        t = rows[-1]["t"]
        coulomb = max(0.0, 0.5 * G * (math.sin(a) - 0.5 * math.cos(a)) * t * t)
        lines.append((angle, i, dt, rc, g(t), g(moved, 4), g(coulomb, 4)))
    table("A particle at rest on a slope, μ 0.5 (friction angle 26.6°): distance slid down the slope",
          ["slope (°)", "integrator", "dt (s)", "exit", "T (s)", "slid (m)", "Coulomb ½g(sinθ−μcosθ)T² (m)"], lines)


def dopri5_bounce(r):
    """dopri5 through contacts: an e = 1 ball for 30 s, and demos/scenes/half-plane.json for 30 s."""
    lines = []
    drop = r.scene(load("elastic-drop.json"))
    with open(os.path.join(ROOT, "demos", "scenes", "half-plane.json")) as f:
        tilted = r.scene(json.load(f))
    runs = [((name, i), path, i, 0.01, 3000, True) for name, path in (("ball on a floor", drop),
                                                                      ("ball on a 10° slope", tilted))
            for i in ("dopri5", "rk4", "verlet")]
    results = r.many(runs)
    for (name, i), (rc, rows, positions) in results.items():
        e0 = rows[0]["total_energy"]
        worst = max(abs(x["total_energy"] - e0) for x in rows) / abs(e0)
        late = [positions[s][0] for s in sorted(positions) if s >= 2500]
        frozen = sum(1 for a, b in zip(late, late[1:]) if a == b)
        lines.append((name, i, rc, "%.2g %%" % (100 * worst), "%d of %d" % (frozen, len(late) - 1)))
    table("Elastic (e = 1) ball dropped from 1 m (on the 10° slope: 1.5 m above the plane), dt 0.01 s, 30 s",
          ["case", "integrator", "exit", "largest \\|ΔE\\|/E₀", "steps of the last 5 s that did not move"], lines)


def capsule(r):
    """10×10 cloth thrown at 20 m/s onto a 10 cm capsule of radius 2 mm; edges cut through its core."""
    source = os.path.join(DATA, "cloth-thrown-at-capsule.json")
    path = r.scene(load("cloth-thrown-at-capsule.json"))
    results = r.many([(i, path, i, 0.002, 500, True) for i in INTEGRATORS])
    lines = []
    for i in INTEGRATORS:
        rc, rows, positions = results[i]
        buffer = io.StringIO()
        buffer.write("step,t,particle,x,y,vx,vy\n")
        for step in sorted(positions):
            for p, (x, y) in positions[step].items():
                buffer.write("%d,0,%d,%r,%r,0,0\n" % (step, p, x, y))
        trajectory = os.path.join(r.work, "capsule-%s.csv" % i)
        with open(trajectory, "w") as f:
            f.write(buffer.getvalue())
        count = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "edge-crossings.py"), source, trajectory],
                               capture_output=True, text=True).stdout.split(" of ")[0]
        lines.append((i, rc, len(rows) - 1, count))
    table("10×10 cloth thrown at 20 m/s onto a 10 cm capsule of radius 2 mm, dt 0.002 s, 1 s "
          "(scripts/edge-crossings.py)", ["integrator", "exit", "steps run", "edges cut through the core"], lines)


def box_of_slabs(moving):
    """40 point particles on the floor of a closed box of four slabs that touch without overlapping."""
    t = 0.05
    slabs = [([-1 - t, -1 - t], [1 + t, -1]), ([-1 - t, 1], [1 + t, 1 + t]), ([-1 - t, -1], [-1, 1]), ([1, -1], [1 + t, 1])]
    particles = []
    for k in range(40):
        x = -1.0 if k == 0 else 1.0 if k == 39 else -0.99 + 0.0495 * k
        v = (0.5 + 2.5 * ((k * 7919) % 40) / 39.0) * (1 if k % 2 else -1) if moving else 0.0
        particles.append({"position": [x, -1.0], "velocity": [v, 0.0], "mass": 1})
    return {"name": "box of four touching slabs", "integrator": "rk4", "dt": 0.005,
            "view": {"min": [-1.2, -1.2], "max": [1.2, 1.2]}, "particles": particles,
            "forces": [{"type": "gravity", "acceleration": [0, -G]}],
            "colliders": [{"type": "box", "min": a, "max": b, "restitution": 0.5, "friction": 0.3} for a, b in slabs]}


def seams(r):
    lines = []
    runs = [((moving, i), r.scene(box_of_slabs(moving)), i, 0.005, 4000, True) for moving in (False, True) for i in INTEGRATORS]
    results = r.many(runs)
    for (moving, i), (rc, rows, positions) in results.items():
        left = set()
        for step, particles in positions.items():
            for p, (x, y) in particles.items():
                if max(abs(x), abs(y)) > 1.0 + 1e-9:
                    left.add(p)
        lines.append(("0.5–3 m/s along the floor" if moving else "at rest", i, rc, "%d of 40" % len(left)))
    table("40 particles on the floor of a box of four touching slabs (μ 0.3, e 0.5), dt 0.005 s, 20 s",
          ["start", "integrator", "exit", "particles that left the box"], lines)


def wedge_scene(alpha):
    b = 0.5 * math.tan(alpha) if alpha < math.radians(5) else 0.01
    return {"name": "wedge", "integrator": "rk4", "dt": 0.001,
            "view": {"min": [-0.1, -0.1], "max": [1.1, 0.6]},
            "particles": [{"position": [1.0, b], "velocity": [-200.0, 0.0], "mass": 1}],
            "colliders": [{"type": "halfPlane", "point": [0, 0], "normal": [0, 1], "restitution": 1, "friction": 0},
                          {"type": "halfPlane", "point": [0, 0], "normal": [math.sin(alpha), -math.cos(alpha)],
                           "restitution": 1, "friction": 0}]}, b


def wedge(r):
    """A point at 200 m/s into a wedge of two elastic half-planes: the exact billiard by unfolding."""
    lines = []
    runs = []
    for degrees in (1.0, 10.0):
        scene, _ = wedge_scene(math.radians(degrees))
        path = r.scene(scene)
        runs += [((degrees, i), path, i, 0.001, 20, True) for i in INTEGRATORS]
    results = r.many(runs)
    for (degrees, i), (rc, rows, positions) in results.items():
        alpha = math.radians(degrees)
        _, b = wedge_scene(alpha)
        worst = 0.0
        for step, particles in positions.items():
            t = 0.001 * step
            ux, uy = 1.0 - 200.0 * t, b
            phi, radius = math.atan2(uy, ux), math.hypot(ux, uy)
            k = math.floor(phi / alpha)
            folded = phi - k * alpha if k % 2 == 0 else (k + 1) * alpha - phi
            x, y = particles[0]
            worst = max(worst, math.hypot(x - radius * math.cos(folded), y - radius * math.sin(folded)))
        lines.append((degrees, i, rc, g(worst)))
    table("A point at 200 m/s into a wedge of two elastic half-planes, dt 0.001 s, 0.02 s (in to the apex and out)",
          ["wedge (°)", "integrator", "exit", "largest distance from the exact billiard (m)"], lines)


CASES = {"chain-floor": chain_on_floor, "chain-slope": chain_on_slope, "wire": wire_and_floor,
         "friction": friction, "dopri5": dopri5_bounce, "capsule": capsule, "seams": seams, "wedge": wedge}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--lab", default=os.path.join(ROOT, "build", "demos", "particle-lab"))
    parser.add_argument("--jobs", type=int, default=len(os.sched_getaffinity(0)))
    parser.add_argument("cases", nargs="*", metavar="CASE", help="any of: " + ", ".join(CASES))
    args = parser.parse_args()
    unknown = [c for c in args.cases if c not in CASES]
    if unknown:
        sys.exit("contact-cases: unknown case %s (known: %s)" % (unknown[0], ", ".join(CASES)))
    if not os.access(args.lab, os.X_OK):
        sys.exit("contact-cases: %s is not an executable; build it or pass --lab" % args.lab)
    with tempfile.TemporaryDirectory() as work:
        runner = Runner(args.lab, work, max(1, args.jobs))
        for name in args.cases or list(CASES):
            CASES[name](runner)


if __name__ == "__main__":
    main()
