#!/usr/bin/env python3
"""Runs the contact cases through `particle-lab run` under every integrator and
prints one Markdown table per case.

    python3 scripts/contact-cases.py [--lab build/demos/particle-lab] [--jobs N] [CASE ...]
    python3 scripts/contact-cases.py --write-scenes   # the judged cases' scene files and references
    python3 scripts/contact-cases.py --check-scenes   # exit 1 when a file differs from its builder

CASE is any of the names below (default: all). Every run is `particle-lab run
--scene-file F --integrator I --dt DT --steps N --threads 1` with --csv (and
--trajectory where positions are judged). Exit codes: 3 is a divergence
(energy blow-up, non-finite state or a failed step), 2 a refused scene file;
the tables show both.

The first cases (chain-floor … wedge) print what each run measured; their
scene files are tests/data/contacts/*.json or built here. The judged cases
(capstan-hold … sleeping-pile, issue 43) each have a criterion: every row of
their table ends with a verdict, "right" or "wrong", a case is right when all
its rows are (rows of a scheme left out, with the reason, do not count), and
the last line counts the cases. Their scene files are written from the
builders below by --write-scenes, so the builders are the one definition of
the geometry, and the closed forms below write tests/data/contacts/references.json;
tests/test_contact_cases.cpp loads both through the scene-file reader.

Capstan with the rope's mass (capstan-hold, capstan-slip, rope-frictionless)
----------------------------------------------------------------------------
A rope of linear density ρ lies on a half circle of radius R (the nodes'
circle: the disc's radius plus the particles') from φ = 0 (right, the light
side) over the top to φ = π (left, the heavy side) and hangs straight down
from both ends, with loads M1 (light) and M2 (heavy). All of it moves with
one speed u = ds/dt along itself, positive when the heavy side goes down;
a = du/dt. On the arc the motion is along t = (−sin φ, cos φ), the outward
normal n = (cos φ, sin φ); an element ρR dφ has tension T(φ), a normal force
N dφ from the disc and, sliding (u > 0), friction −μN dφ along t. Gravity
has components −g cos φ along t and −g sin φ along n; the element's
acceleration is a along t and u²/R inwards, so per dφ:
    normal:      N − T − ρRg sin φ = −ρu²          ⇒ N = T + ρRg sin φ − ρu²
    tangential:  dT/dφ − μN − ρRg cos φ = ρRa
    ⇒ dT/dφ − μT = μρRg sin φ + ρRg cos φ − μρu² + ρRa,
linear in T, so with E = e^{μπ}, ∫₀^π e^{μ(π−φ)} sin φ dφ = (1 + E)/(1 + μ²),
∫₀^π e^{μ(π−φ)} cos φ dφ = μ(1 + E)/(1 + μ²) and ∫₀^π e^{μ(π−φ)} dφ = (E − 1)/μ
(→ π as μ → 0):
    T(π) = E T(0) + 2μ(1 + E)/(1 + μ²) ρRg − (E − 1) ρu² + (E − 1)/μ ρRa.
The hanging parts, of lengths L1 = L1(0) − s and L2 = L2(0) + s, are straight
and move with the rope (the light one up, the heavy one down):
    T(0) = (M1 + ρL1)(g + a),    T(π) = (M2 + ρL2)(g − a).
The two expressions of T(π) are one linear condition on a:
    a = [(M2 + ρL2)g − E(M1 + ρL1)g − 2μ(1 + E)/(1 + μ²) ρRg + (E − 1)ρu²]
        / [M2 + ρL2 + E(M1 + ρL1) + (E − 1)/μ ρR].
With ρ = 0 it is the massless capstan a = g(M2 − M1 E)/(M2 + M1 E); with
μ = 0 Atwood's machine with its rope, a = g(M2 − M1 + ρ(L2 − L1))/(M1 + M2 +
ρ(L1 + L2 + πR)) (both checked by the capstan cases' header, which prints
them). The drop s(t) solves s'' = a(s, s') from rest, integrated by fixed-step
RK4 with h = 1e-3 s; the header prints s(T) at h, h/2 and h/4 (they agree to
1e-12 m). The solution holds while u ≥ 0, L1 ≥ 0 and N ≥ 0 all along the arc
(checked at 181 angles at the end of the run). A rope at rest holds when it
would slide neither way: a(0, 0) ≤ 0 with μ, and a(0, 0) ≥ 0 with −μ (sliding
back reverses the friction).
The scene's rope is 49 particles and 48 rods: the two ends carry the loads
(masses M1, M2), the 47 others m = 2 g each, and each particle stands for the
rope within l/2 of it, so ρ = m/l and the continuous rope's loads are M_i − m/2.
Its 20 arc segments are chords, l = 2R sin(π/40); the polygon's own capstan
factor, the product over its nodes of (1 + μ tan(β/2))/(1 − μ tan(β/2)) for
turning angles β (π/20 inside, π/40 at the arc's ends), is 0.2% above e^{μπ};
the header prints how far that moves the reference (the rest of the error of
a 48-rod rope against the continuum is of the same order, δ² = (π/20)²).

Strand over a ledge (strand-ledge)
----------------------------------
A strand of bending stiffness EI = k l (angle springs k at its nodes, links
l) and weight w = m g / l per length lies on the frictionless top of a box,
pinned far back, and runs past the box's corner by b. Near the corner it
lifts off the top over a length c. On [−c, 0] (x from the corner) it carries
its own weight between the lift-off point, where y = y' = 0 and the bending
moment is 0 (a concentrated reaction R_c acts there), and the corner, y(0) = 0:
    M(x) = R_c (x + c) − w (x + c)²/2,   EI y = R_c (x + c)³/6 − w (x + c)⁴/24;
y(0) = 0 gives R_c = wc/4, so M(0) = −wc²/4, which must be the overhang's
moment −wb²/2: c = √2 b, and the slope at the corner is
y'(0) = −wc³/(24 EI) = −√2 w b³/(12 EI). The overhang is a cantilever leaving
the corner at that slope, so the tip deflection is
    δ = √2 w b⁴/(12 EI) + w b⁴/(8 EI) = (√2/12 + 1/8) w b⁴/EI ≈ 0.2428 w b⁴/EI.
The scene lumps the strand at its particles (the tip particle has m/2); the
header checks the formula against the small-deflection statics of those very
particles (the energy Σ ½k((y_{i+1} − 2y_i + y_{i−1})/l)² + Σ m_i g y_i
minimised with y_i ≥ 0 over the top and the link over the corner above the
corner, by active sets) and judges the runs against that discrete model.
"""
import argparse
import collections
import concurrent.futures
import csv
import io
import json
import math
import os
import random
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
        result = self.result(scene_path, integrator, dt, steps, 1 if trajectory else 0)
        return result.code, result.rows, result.positions

    def result(self, scene_path, integrator, dt, steps, every=0):
        """One run as a Result: the exit code, the CSV rows as dicts of floats, the trajectory
        every `every` steps (0: none) as {step: {particle: (x, y)}} and {step: {particle: (vx, vy)}},
        and the last line of stderr."""
        tag = "%s-%s-%g-%d" % (os.path.basename(scene_path), integrator, dt, steps)
        out_csv = os.path.join(self.work, tag + ".csv")
        out_traj = os.path.join(self.work, tag + ".traj.csv")
        command = [self.lab, "run", "--scene-file", scene_path, "--integrator", integrator, "--dt", repr(dt),
                   "--steps", str(steps), "--csv", out_csv, "--threads", "1"]
        if every:
            command += ["--trajectory", out_traj, "--every", str(every)]
        done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        rows = []
        if os.path.exists(out_csv):
            with open(out_csv) as f:
                rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
            os.remove(out_csv)
        positions, velocities = {}, {}
        if every and os.path.exists(out_traj):
            with open(out_traj) as f:
                for r in csv.DictReader(f):
                    step, particle = int(r["step"]), int(r["particle"])
                    positions.setdefault(step, {})[particle] = (float(r["x"]), float(r["y"]))
                    velocities.setdefault(step, {})[particle] = (float(r["vx"]), float(r["vy"]))
            os.remove(out_traj)
        error = done.stderr.strip().splitlines()[-1] if done.stderr.strip() else ""
        error = error.replace("particle-lab: ", "").replace(scene_path + ": ", "").replace("|", "/").split(" (valid here")[0]
        return Result(done.returncode, rows, positions, velocities, error)

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



# ---- the judged cases (issue 43): geometry ---------------------------------
# Each builder returns a scene as a dict; SCENES names the files they are
# written to. Units SI, g = 9.81 m/s².

ROPE = {"disc": 0.3, "arc": 20, "hang": 14, "mass": 0.002, "light": 0.4, "dt": 0.002}


def rope_geometry(radius):
    """The capstan rope's nodes' circle (the disc grown by the particles' radius) and rod length."""
    circle = ROPE["disc"] + radius
    return circle, 2 * circle * math.sin(math.pi / (2 * ROPE["arc"]))


def capstan_scene(name, ratio, mu, radius=0.0):
    """48 rods over a fixed disc (centre 0, R 0.3 m): 14 hang on the right to the light end
    (particle 0, 0.4 kg), 20 lie on the upper half circle, 14 hang on the left to the heavy
    end (particle 48, ratio × 0.4 kg); the other particles 2 g."""
    circle, rod = rope_geometry(radius)
    hang, arc = ROPE["hang"], ROPE["arc"]
    points = [(circle, -(hang - k) * rod) for k in range(hang)]
    points += [(circle * math.cos(math.pi * k / arc), circle * math.sin(math.pi * k / arc)) for k in range(arc + 1)]
    points += [(-circle, -k * rod) for k in range(1, hang + 1)]
    particles = []
    for i, p in enumerate(points):
        mass = ROPE["light"] if i == 0 else ratio * ROPE["light"] if i == len(points) - 1 else ROPE["mass"]
        particle = {"position": list(p), "mass": mass}
        if radius > 0:
            particle["radius"] = radius
        particles.append(particle)
    return {"name": name, "integrator": "rk4", "dt": ROPE["dt"],
            "view": {"min": [-0.8, -0.9], "max": [0.8, 0.5]}, "particles": particles,
            "forces": [{"type": "gravity", "acceleration": [0, -G]}],
            "constraints": [{"type": "rod", "particles": [i, i + 1], "length": rod} for i in range(len(points) - 1)],
            "colliders": [{"type": "disc", "centre": [0, 0], "radius": ROPE["disc"], "restitution": 0, "friction": mu}]}


def chain(first, step, count, mass, radius=0.0):
    """count particles from `first` in steps of `step`, joined by rods."""
    particles = []
    for k in range(count):
        particle = {"position": [first[0] + k * step[0], first[1] + k * step[1]], "mass": mass}
        if radius > 0:
            particle["radius"] = radius
        particles.append(particle)
    length = math.hypot(*step)
    return particles, [{"type": "rod", "particles": [k, k + 1], "length": length} for k in range(count - 1)]


def slope_plane(degrees, mu, e):
    a = math.radians(degrees)
    return {"type": "halfPlane", "point": [0, 0], "normal": [-math.sin(a), math.cos(a)], "restitution": e, "friction": mu}


def disc_chain_floor():
    """10 rods of 0.1 m, 11 discs of 1 cm and 0.1 kg, pinned at the origin, released level
    above a floor 0.6 m below the pin (e 0.5, μ 0.3)."""
    particles, rods = chain((0.0, 0.0), (0.1, 0.0), 11, 0.1, radius=0.01)
    particles[0]["pinned"] = True
    return {"name": "disc chain lands on a floor", "integrator": "rk4", "dt": 0.002,
            "view": {"min": [-1.2, -0.8], "max": [1.2, 0.3]}, "particles": particles,
            "forces": [{"type": "gravity", "acceleration": [0, -G]}], "constraints": rods,
            "colliders": [{"type": "halfPlane", "point": [0, -0.6], "normal": [0, 1], "restitution": 0.5, "friction": 0.3}]}


def disc_chain_slope():
    """The same chain, free, level, dropped onto a 20° slope through the origin (μ 0.5, e 0.5):
    its right end starts 0.2 m above the slope."""
    top = 0.5 * math.tan(math.radians(20)) + 0.2 + 0.01
    particles, rods = chain((-0.5, top), (0.1, 0.0), 11, 0.1, radius=0.01)
    return {"name": "disc chain dropped on a slope", "integrator": "rk4", "dt": 0.002,
            "view": {"min": [-1.5, -1.0], "max": [1.5, 1.0]}, "particles": particles,
            "forces": [{"type": "gravity", "acceleration": [0, -G]}], "constraints": rods,
            "colliders": [slope_plane(20, 0.5, 0.5)]}


def falling_edge(name, height, collider):
    """Two 10 g particles 5 cm apart joined by a spring and a collision edge, level and centred
    on x = 0 at `height`, falling onto `collider`; a floor 0.1 m below the origin."""
    return {"name": name, "integrator": "rk4", "dt": 0.001,
            "view": {"min": [-0.15, -0.12], "max": [0.15, 0.08]},
            "particles": [{"position": [-0.025, height], "mass": 0.01}, {"position": [0.025, height], "mass": 0.01}],
            "forces": [{"type": "gravity", "acceleration": [0, -G]},
                       {"type": "spring", "particles": [0, 1], "restLength": 0.05, "stiffness": 100, "damping": 0.1}],
            "colliders": [collider, {"type": "halfPlane", "point": [0, -0.1], "normal": [0, 1], "restitution": 0, "friction": 0.3}],
            "collisionEdges": [[0, 1]]}


def edge_on_apex():
    """The edge 1 mm above the apex (0, 0) of a right-angled triangle standing on the floor."""
    apex = {"type": "polygon", "vertices": [[-0.1, -0.1], [0.1, -0.1], [0, 0]], "restitution": 0, "friction": 0.3}
    return falling_edge("edge dropped on a triangle's apex", 0.001, apex)


def edge_on_post():
    """The edge 2 cm above a post 4 mm wide (top corners (±0.002, 0)) standing on the floor."""
    post = {"type": "box", "min": [-0.002, -0.1], "max": [0.002, 0.0], "restitution": 0, "friction": 0.3}
    return falling_edge("edge dropped on a 4 mm post", 0.02, post)


def chain_on_slope_at_rest():
    """7 rods of 0.1 m (8 particles of 0.1 kg) lying at rest along a 20° slope, μ 0.5 (friction
    angle 26.6°), e 0; the lowest particle 0.5 m up the slope from the origin."""
    a = math.radians(20)
    along = (0.1 * math.cos(a), 0.1 * math.sin(a))
    particles, rods = chain((5 * along[0], 5 * along[1]), along, 8, 0.1)
    return {"name": "7-rod chain at rest on a 20° slope", "integrator": "rk4", "dt": 0.002,
            "view": {"min": [-0.2, -0.2], "max": [1.5, 0.8]}, "particles": particles,
            "forces": [{"type": "gravity", "acceleration": [0, -G]}], "constraints": rods,
            "colliders": [slope_plane(20, 0.5, 0.0)]}


def open_box(width, height, e, mu):
    """A floor and two walls (boxes 0.1 m thick that touch), inner width `width`, floor top at y = 0."""
    h, t = 0.5 * width, 0.1
    slabs = [([-h - t, -t], [h + t, 0.0]), ([-h - t, 0.0], [-h, height]), ([h, 0.0], [h + t, height])]
    return [{"type": "box", "min": a, "max": b, "restitution": e, "friction": mu} for a, b in slabs]


def disc_pile():
    """200 discs, radii uniform in [2.5, 3.5] cm, mass 0.1 kg × (r / 3 cm)², on a 12-wide grid of
    8 cm from 5 cm above the floor, velocities uniform in a disc of 0.3 m/s (seed 43), into a
    box 1 m wide (e 0.2, μ 0.5); disc–disc e 0.2 and friction 0.5 (particleFriction)."""
    rng = random.Random(43)
    particles = []
    for k in range(200):
        r = 0.025 + 0.01 * rng.random()
        speed, angle = 0.3 * math.sqrt(rng.random()), 2 * math.pi * rng.random()
        particles.append({"position": [-0.44 + 0.08 * (k % 12), 0.05 + 0.08 * (k // 12)],
                          "velocity": [speed * math.cos(angle), speed * math.sin(angle)],
                          "mass": 0.1 * (r / 0.03) ** 2, "radius": r})
    return {"name": "pile of 200 discs", "integrator": "rk4", "dt": 0.002,
            "view": {"min": [-0.7, -0.2], "max": [0.7, 1.6]}, "particleRestitution": 0.2, "particleFriction": 0.5,
            "particles": particles, "forces": [{"type": "gravity", "acceleration": [0, -G]}],
            "colliders": open_box(1.0, 2.0, 0.2, 0.5)}


def box_of_slabs_bouncing(walls_outside):
    """40 point particles thrown up from the floor of the closed box of four touching slabs
    (box_of_slabs) at 0–0.5 m/s and along it at 0.5–3 m/s, e 0.9, μ 0.3: they hop, then
    slide. walls_outside: the box_of_slabs tiling (floor and ceiling the full width, the
    walls between them); otherwise the corners cut the other way (walls the full height,
    floor and ceiling between them), whose floor–wall seams let a sliding particle through."""
    scene = box_of_slabs(True)
    scene["name"] = "box of four touching slabs, bouncing" + ("" if walls_outside else ", walls the full height")
    for k, particle in enumerate(scene["particles"]):
        particle["velocity"][1] = 0.5 * ((k * 104729) % 40) / 39.0
    if not walls_outside:
        t = 0.05
        slabs = [([-1, -1 - t], [1, -1]), ([-1, 1], [1, 1 + t]), ([-1 - t, -1 - t], [-1, 1 + t]), ([1, -1 - t], [1 + t, 1 + t])]
        scene["colliders"] = [dict(c, min=a, max=b) for c, (a, b) in zip(scene["colliders"], slabs)]
    for collider in scene["colliders"]:
        collider["restitution"] = 0.9
    return scene


def ribbon_over_disc():
    """A strip of 2 × 31 particles (5 g, 2 cm apart) joined along, across and diagonally by springs
    (k 500 N/m, k_d 0.05), its rows and rungs collision edges, level and centred 2 mm above a disc
    (centre 0, R 0.1 m, μ 0.5, e 0): it drapes symmetrically."""
    columns, spacing, radius = 31, 0.02, 0.1
    particles = []
    for row in range(2):
        for c in range(columns):
            particles.append({"position": [(c - (columns - 1) / 2) * spacing, radius + 0.002 + row * spacing],
                              "mass": 0.005})
    at = lambda row, c: row * columns + c
    springs, edges = [], []

    def spring(i, j):
        a, b = particles[i]["position"], particles[j]["position"]
        springs.append({"type": "spring", "particles": [i, j], "restLength": math.hypot(a[0] - b[0], a[1] - b[1]),
                        "stiffness": 500, "damping": 0.05})

    for c in range(columns):
        spring(at(0, c), at(1, c))
        edges.append([at(0, c), at(1, c)])
        if c + 1 < columns:
            for row in range(2):
                spring(at(row, c), at(row, c + 1))
                edges.append([at(row, c), at(row, c + 1)])
            spring(at(0, c), at(1, c + 1))
            spring(at(1, c), at(0, c + 1))
    return {"name": "ribbon draped over a disc", "integrator": "rk4", "dt": 0.002,
            "view": {"min": [-0.4, -0.3], "max": [0.4, 0.2]}, "particles": particles,
            "forces": [{"type": "gravity", "acceleration": [0, -G]}] + springs,
            "colliders": [{"type": "disc", "centre": [0, 0], "radius": radius, "restitution": 0, "friction": 0.5}],
            "collisionEdges": edges}


STRAND = {"links": 30, "corner": 20, "rod": 0.05, "mass": 0.005, "stiffness": 10.0, "drag": 0.1, "dt": 0.0004}


def strand_over_ledge():
    """31 particles (5 g; the tip 2.5 g) on rods of 5 cm with angle springs (k 10 N·m/rad, rest
    straight) at every inner particle and a collision edge on every link, lying on the
    frictionless top (y = 0) of a box whose corner (0, 0) lies in the middle of link 20: the
    root (particle 0) is pinned 1.025 m back, the tip 0.475 m past the corner. Drag 0.1 N·s/m
    on every particle (no stiffness-proportional damping, which would bound an explicit dt)."""
    n, j, l = STRAND["links"], STRAND["corner"], STRAND["rod"]
    particles, rods = chain((-(j + 0.5) * l, 0.0), (l, 0.0), n + 1, STRAND["mass"])
    particles[0]["pinned"] = True
    particles[-1]["mass"] = STRAND["mass"] / 2
    bends = [{"type": "angular-spring", "particles": [i - 1, i, i + 1], "restAngle": math.pi,
              "stiffness": STRAND["stiffness"], "damping": 0} for i in range(1, n)]
    return {"name": "strand over a ledge", "integrator": "rk4", "dt": STRAND["dt"],
            "view": {"min": [-1.2, -0.4], "max": [0.7, 0.3]}, "particles": particles,
            "forces": [{"type": "gravity", "acceleration": [0, -G]}, {"type": "drag", "damping": STRAND["drag"]}] + bends,
            "constraints": rods,
            "colliders": [{"type": "box", "min": [-1.5, -0.3], "max": [0, 0], "restitution": 0, "friction": 0}],
            "collisionEdges": [[i, i + 1] for i in range(n)]}


CRADLE = {"radius": 0.02, "mass": 0.1, "string": 0.5, "raise": 0.05}


def free_cradle():
    """5 equal discs (2 cm, 0.1 kg), the last four touching in a row, the first 1 cm from them
    moving in at 1 m/s; no gravity, disc–disc e 1."""
    d = 2 * CRADLE["radius"]
    particles = [{"position": [-0.01, 0], "velocity": [1.0, 0.0], "mass": CRADLE["mass"], "radius": CRADLE["radius"]}]
    particles += [{"position": [d * k, 0], "mass": CRADLE["mass"], "radius": CRADLE["radius"]} for k in range(1, 5)]
    return {"name": "free Newton's cradle", "integrator": "rk4", "dt": 0.001,
            "view": {"min": [-0.1, -0.1], "max": [0.3, 0.1]}, "particleRestitution": 1, "particles": particles}


def hung_cradle():
    """5 equal discs (2 cm, 0.1 kg) each on a 0.5 m rod to its own pinned pivot, touching at the
    bottom; the first raised by h = 5 cm; disc–disc e 1."""
    d, length, h = 2 * CRADLE["radius"], CRADLE["string"], CRADLE["raise"]
    swing = math.acos(1 - h / length)
    particles, rods = [], []
    for k in range(5):
        pivot = [d * k, length]
        bob = [pivot[0] - length * math.sin(swing), h] if k == 0 else [d * k, 0.0]
        particles += [{"position": pivot, "mass": 1, "pinned": True},
                      {"position": bob, "mass": CRADLE["mass"], "radius": CRADLE["radius"]}]
        rods.append({"type": "rod", "particles": [2 * k, 2 * k + 1], "length": length})
    return {"name": "hung Newton's cradle", "integrator": "rk4", "dt": 0.001,
            "view": {"min": [-0.3, -0.1], "max": [0.5, 0.6]}, "particleRestitution": 1, "particles": particles,
            "forces": [{"type": "gravity", "acceleration": [0, -G]}], "constraints": rods}


SLEEP = {"rows": [8, 7, 6, 5], "radius": 0.03}


def sleeping_pile():
    """26 discs (3 cm, 0.1 kg) stacked touching in rows of 8, 7, 6, 5 between two walls that
    touch the bottom row, at rest (e 0.2, μ 0.5); a 27th disc thrown up from 0.5 m above the
    pile's top at 4 m/s falls back onto it after 0.93 s at 5.1 m/s."""
    r = SLEEP["radius"]
    particles = []
    for row, count in enumerate(SLEEP["rows"]):
        for k in range(count):
            particles.append({"position": [(k - (count - 1) / 2) * 2 * r, r + row * r * math.sqrt(3)],
                              "mass": 0.1, "radius": r, "velocity": [0, 0]})
    top = r + (len(SLEEP["rows"]) - 1) * r * math.sqrt(3) + r
    particles.append({"position": [0.01, top + 0.5 + r], "velocity": [0, 4.0], "mass": 0.1, "radius": r})
    return {"name": "sleeping pile woken by a dropped disc", "integrator": "rk4", "dt": 0.002,
            "view": {"min": [-0.4, -0.1], "max": [0.4, 1.8]}, "particleRestitution": 0.2, "particles": particles,
            "forces": [{"type": "gravity", "acceleration": [0, -G]}],
            "colliders": open_box(SLEEP["rows"][0] * 2 * r, 0.6, 0.2, 0.5)}


SCENES = {
    "capstan-hold.json": lambda: capstan_scene("capstan: rope holds, end masses 1:2.2, μ 0.3", 2.2, 0.3),
    "capstan-hold-discs.json": lambda: capstan_scene("capstan: rope of 4 mm discs holds, 1:2.2, μ 0.3", 2.2, 0.3, 0.004),
    "capstan-slip.json": lambda: capstan_scene("capstan: rope slips, end masses 1:3, μ 0.3", 3.0, 0.3),
    "capstan-slip-discs.json": lambda: capstan_scene("capstan: rope of 4 mm discs slips, 1:3, μ 0.3", 3.0, 0.3, 0.004),
    "rope-frictionless.json": lambda: capstan_scene("rope slides over a frictionless disc, 1:1.2", 1.2, 0.0),
    "disc-chain-floor.json": disc_chain_floor,
    "disc-chain-slope.json": disc_chain_slope,
    "edge-on-apex.json": edge_on_apex,
    "edge-on-post.json": edge_on_post,
    "chain-rest-on-slope.json": chain_on_slope_at_rest,
    "disc-pile.json": disc_pile,
    "box-of-slabs-bouncing.json": lambda: box_of_slabs_bouncing(True),
    "box-of-slabs-bouncing-walls.json": lambda: box_of_slabs_bouncing(False),
    "ribbon-over-disc.json": ribbon_over_disc,
    "strand-over-ledge.json": strand_over_ledge,
    "cradle-free.json": free_cradle,
    "cradle-hung.json": hung_cradle,
    "sleeping-pile.json": sleeping_pile,
}


def scene_text(scene):
    """A scene as JSON with each particle, force, constraint, collider and edge on its own line."""
    lines = []
    for key, value in scene.items():
        if isinstance(value, list) and value and isinstance(value[0], (dict, list)):
            body = ",\n  ".join(json.dumps(item) for item in value)
            lines.append("%s: [\n  %s\n]" % (json.dumps(key), body))
        else:
            lines.append("%s: %s" % (json.dumps(key), json.dumps(value)))
    return "{\n" + ",\n".join(lines) + "\n}\n"


# ---- closed forms ------------------------------------------------------------

Rope = collections.namedtuple("Rope", "light heavy density light_hang heavy_hang radius mu")


def rope_of(ratio, mu, radius=0.0):
    """The continuous rope equivalent to capstan_scene(ratio, mu, radius) (see the docstring)."""
    circle, rod = rope_geometry(radius)
    m = ROPE["mass"]
    return Rope(ROPE["light"] - m / 2, ratio * ROPE["light"] - m / 2, m / rod, ROPE["hang"] * rod,
                ROPE["hang"] * rod, circle, mu)


def capstan_terms(mu, polygon_factor=None):
    """E = e^{μπ} (or a given factor), (E − 1)/μ and 2μ(1 + E)/(1 + μ²), with their μ → 0 limits."""
    e = polygon_factor if polygon_factor is not None else math.exp(mu * math.pi)
    inertia = (e - 1) / mu if mu != 0 else math.pi
    return e, inertia, 2 * mu * (1 + e) / (1 + mu * mu)


def capstan_acceleration(rope, s, u, polygon_factor=None):
    """a of the two-point condition (docstring) at drop s and speed u ≥ 0 (sliding forward)."""
    e, inertia, weight_on_arc = capstan_terms(rope.mu, polygon_factor)
    light = rope.light + rope.density * (rope.light_hang - s)
    heavy = rope.heavy + rope.density * (rope.heavy_hang + s)
    pull = (heavy - e * light) * G - weight_on_arc * rope.density * rope.radius * G + (e - 1) * rope.density * u * u
    return pull / (heavy + e * light + inertia * rope.density * rope.radius)


def capstan_drop(rope, duration, h=1e-3, polygon_factor=None):
    """(s, u) at `duration` from rest, by fixed-step RK4 on s'' = a(s, s')."""
    s, u = 0.0, 0.0
    f = lambda s, u: capstan_acceleration(rope, s, u, polygon_factor)
    for _ in range(int(round(duration / h))):
        k1 = (u, f(s, u))
        k2 = (u + 0.5 * h * k1[1], f(s + 0.5 * h * k1[0], u + 0.5 * h * k1[1]))
        k3 = (u + 0.5 * h * k2[1], f(s + 0.5 * h * k2[0], u + 0.5 * h * k2[1]))
        k4 = (u + h * k3[1], f(s + h * k3[0], u + h * k3[1]))
        s += h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        u += h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
    return s, u


def capstan_least_normal_force(rope, s, u):
    """min over 181 angles of N(φ) = T(φ) + ρRg sin φ − ρu² per radian (N), T from T(0) by the
    arc's linear ODE (docstring) solved in closed form."""
    mu, rho, radius = rope.mu, rope.density, rope.radius
    a = capstan_acceleration(rope, s, u)
    start = (rope.light + rho * (rope.light_hang - s)) * (G + a)
    least = float("inf")
    for k in range(181):
        phi = math.pi * k / 180
        decay = math.exp(-mu * phi)
        sin_integral = (1 - decay * (mu * math.sin(phi) + math.cos(phi))) / (1 + mu * mu)
        cos_integral = (decay * (math.sin(phi) - mu * math.cos(phi)) + mu) / (1 + mu * mu)
        one_integral = (1 - decay) / mu if mu != 0 else phi
        tension = (start + mu * rho * radius * G * sin_integral + rho * radius * G * cos_integral
                   + (rho * radius * a - mu * rho * u * u) * one_integral) / decay
        least = min(least, tension + rho * radius * G * math.sin(phi) - rho * u * u)
    return least


def capstan_holds(rope):
    """At rest, slides neither forward (a ≤ 0 with μ) nor back (a ≥ 0 with −μ)."""
    back = rope._replace(mu=-rope.mu)
    return capstan_acceleration(rope, 0, 0) <= 0 and capstan_acceleration(back, 0, 0) >= 0


def polygon_capstan_factor(mu):
    """The capstan factor of the scene's 20-chord arc with its nodes on the circle (docstring)."""
    beta = math.pi / ROPE["arc"]
    node = lambda turn: (1 + mu * math.tan(turn / 2)) / (1 - mu * math.tan(turn / 2))
    return node(beta) ** (ROPE["arc"] - 1) * node(beta / 2) ** 2


def solve_dense(a, b):
    """x with a x = b, by Gaussian elimination with partial pivoting (small systems)."""
    n = len(b)
    m = [row[:] + [b[i]] for i, row in enumerate(a)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(m[r][c]))
        m[c], m[p] = m[p], m[c]
        for r in range(c + 1, n):
            f = m[r][c] / m[c][c]
            if f:
                for k in range(c, n + 1):
                    m[r][k] -= f * m[c][k]
    x = [0.0] * n
    for r in reversed(range(n)):
        x[r] = (m[r][n] - sum(m[r][k] * x[k] for k in range(r + 1, n))) / m[r][r]
    return x


def strand_continuum_tip():
    """δ = (√2/12 + 1/8) w b⁴/EI (docstring), b from the corner to the tip."""
    l = STRAND["rod"]
    b = (STRAND["links"] - STRAND["corner"] - 0.5) * l
    return (math.sqrt(2) / 12 + 1 / 8) * (STRAND["mass"] * G / l) * b ** 4 / (STRAND["stiffness"] * l)


def strand_discrete_tip(support=None, top=None):
    """The tip's drop in the small-deflection statics of the scene's particles (docstring):
    heights y_1..y_n (y_0 = 0, pinned), the particles 1..p on the top (y = 0) and the support
    on it: by default the link over the corner, (y_j + y_{j+1})/2 = 0 (`support` maps particles
    to weights, `top` is the last particle over the top, j by default). The p whose solution
    is feasible (particles p+1..top above the top, every reaction pushing up) is the answer.
    Returns (drop, p)."""
    n, j, l, k = STRAND["links"], STRAND["corner"], STRAND["rod"], STRAND["stiffness"]
    support = support or {j: 0.5, j + 1: 0.5}
    top = j if top is None else top
    weight = [STRAND["mass"] * G] * n
    weight[-1] /= 2
    stiffness = [[0.0] * n for _ in range(n)]  # K of ½ k Σ κ_i², κ_i = (y_{i+1} − 2y_i + y_{i−1})/l
    for i in range(1, n):
        stencil = {i - 1: 1.0, i: -2.0, i + 1: 1.0}
        for a, ca in stencil.items():
            for b, cb in stencil.items():
                if a > 0 and b > 0:
                    stiffness[a - 1][b - 1] += k / l ** 2 * ca * cb
    for p in range(0, top + 1):
        rows = [{i: 1.0} for i in range(1, p + 1)] + [support]
        size = n + len(rows)
        kkt = [[0.0] * size for _ in range(size)]
        rhs = [-w for w in weight] + [0.0] * len(rows)
        for a in range(n):
            kkt[a][:n] = stiffness[a][:]
        for c, row in enumerate(rows):
            for i, v in row.items():
                kkt[i - 1][n + c] = -v
                kkt[n + c][i - 1] = v
        solution = solve_dense(kkt, rhs)
        y, reactions = solution[:n], solution[n:]
        if all(r >= -1e-12 for r in reactions) and all(y[i - 1] >= -1e-12 for i in range(p + 1, top + 1)):
            return -y[-1], p
    raise RuntimeError("strand model: no contact set is feasible")


def references():
    """The closed forms' numbers that tests/test_contact_cases.cpp asserts against."""
    return {
        "capstan-slip.json": {"drop": capstan_drop(rope_of(3.0, 0.3), 1.0)[0], "time": 1.0},
        "capstan-slip-discs.json": {"drop": capstan_drop(rope_of(3.0, 0.3, 0.004), 1.0)[0], "time": 1.0},
        "rope-frictionless.json": {"drop": capstan_drop(rope_of(1.2, 0.0), 1.0)[0], "time": 1.0},
        "strand-over-ledge.json": {"tip": strand_discrete_tip()[0]},
    }


def reference_text():
    return json.dumps(references(), indent=1, sort_keys=True) + "\n"


# ---- the judged cases: plans, cells and tables --------------------------------

Run = collections.namedtuple("Run", "scene variant integrator dt steps every")
Result = collections.namedtuple("Result", "code rows positions velocities error")


class Case:
    """A judged case: what it runs (plan), how one run is judged (cell: the row's measured
    columns and whether it meets the criterion), and the table's title and header."""

    def __init__(self, name, title, criterion, header, plan, cell, note=None):
        self.name, self.title, self.criterion, self.header = name, title, criterion, header
        self.plan, self.cell, self.note = plan, cell, note


def every_integrator(scene, dts, duration, every=0, leave_out=()):
    """Runs of `scene` under every integrator at each dt for `duration`, every `every` seconds
    on the trajectory (0: none). A scheme in leave_out (a name, or (name, dt) for one dt only)
    is run on the scene without its colliders and edges instead: the reason it is left out."""
    runs = []
    for dt in dts:
        for i in INTEGRATORS:
            variant = "no contact" if i in leave_out or (i, dt) in leave_out else ""
            runs.append(Run(scene, variant, i, dt, int(round(duration / dt)), every and max(1, int(round(every / dt)))))
    return runs


def scene_of(run):
    """The run's scene: its builder's, or a variant of it (without contacts; without the
    particleFriction key, which today's reader refuses)."""
    scene = SCENES[run.scene]()
    if run.variant == "no contact":
        scene = dict(scene, colliders=[], collisionEdges=[])
    elif run.variant == "no particleFriction":
        scene = {k: v for k, v in scene.items() if k != "particleFriction"}
    elif run.variant == "line support":
        scene = strand_on_line(scene)
    return scene


def strand_on_line(scene):
    """The strand held up at particle `corner` by a horizontal line constraint instead of the
    ledge's corner, the ledge's top cut back to x = −0.3 (under particles 0..14 only, below the
    lifted strand): a check of the strand model on contacts that today's engine gets right
    (particles on a face), against strand_discrete_tip({corner: 1}, 14)."""
    j, l = STRAND["corner"], STRAND["rod"]
    ledge = dict(scene["colliders"][0], max=[-0.3, 0])
    line = {"type": "line", "particle": j, "point": [-0.5 * l, 0], "angle": 0}
    return dict(scene, colliders=[ledge], constraints=scene["constraints"] + [line])


def failure(result):
    """'' for a run that completed, else what stopped it."""
    if result.code == 0:
        return ""
    return "exit %d: %s" % (result.code, result.error or "no message")


def left_out(run, result):
    """The row of a scheme left out: run on the scene without contacts, where it diverges."""
    if result.code == 3:
        return ["left out: diverges without any contact"], None
    return ["left out, but runs without contact: put it back"], None


def worst_rod(result, length):
    return max(r["max_constraint_error"] for r in result.rows) / length if result.rows else float("nan")


def judged(values, right, result):
    """A row's measured columns and its verdict: right when the criterion holds and the run completed."""
    return values, bool(right) and not failure(result)


def capstan_hold_cell(run, result):
    if run.variant:
        return left_out(run, result)
    steps = sorted(result.positions)
    heavy = [result.positions[s][48] for s in steps]
    moved = max(math.hypot(x - heavy[0][0], y - heavy[0][1]) for x, y in heavy) if heavy else float("nan")
    return judged(["%.3g" % (1000 * moved)], moved <= 1e-3, result)


def slip_cell(ratio, mu, radius, tolerance, rod_limit=None):
    def cell(run, result):
        if run.variant == "no contact":
            return left_out(run, result)
        reference = capstan_drop(rope_of(ratio, mu, radius), run.dt * run.steps)[0]
        judge = run.variant != "convergence"
        steps = sorted(result.positions)
        drop = result.positions[steps[0]][48][1] - result.positions[steps[-1]][48][1] if steps else float("nan")
        reached = steps and steps[-1] == run.steps
        error = (drop - reference) / reference
        rod = worst_rod(result, rope_geometry(radius)[1])
        right = reached and abs(error) <= tolerance and (rod_limit is None or rod <= rod_limit)
        values, right = judged(["%.1f" % (1000 * drop), "%.1f" % (1000 * reference), "%+.1f %%" % (100 * error),
                                "%.3g %%" % (100 * rod)], right, result)
        return values, right if judge else None
    return cell


def rod_cell(length, limit):
    def cell(run, result):
        if run.variant == "no contact":
            return left_out(run, result)
        rod = worst_rod(result, length)
        return judged(["%.3g %%" % (100 * rod), g(energy_rise(result.rows))], rod <= limit, result)
    return cell


def edge_cell(run, result):
    """Corners that an edge passed (scripts/edge-crossings.py over the trajectory, every step)."""
    lines = ["step,t,particle,x,y,vx,vy"]
    for step in sorted(result.positions):
        for p, (x, y) in result.positions[step].items():
            lines.append("%d,0,%d,%r,%r,0,0" % (step, p, x, y))
    with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
        f.write("\n".join(lines) + "\n")
    try:
        with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as scene:
            scene.write(scene_text(scene_of(run)))
        out = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "edge-crossings.py"), scene.name, f.name],
                             capture_output=True, text=True).stdout.strip()
    finally:
        os.remove(f.name)
        os.remove(scene.name)
    cut = int(out.split(" ")[0]) if out[:1].isdigit() else -1
    final = result.positions[max(result.positions)] if result.positions else {}
    height = min(p[1] for p in final.values()) if final else float("nan")
    return judged([out.split(" edges")[0], "%.4g" % height], cut == 0, result)


def creep_cell(run, result):
    a = math.radians(20)
    steps = sorted(result.positions)
    centre = lambda s: sum(p[0] * math.cos(a) + p[1] * math.sin(a) for p in result.positions[s].values()) / 8
    duration = run.dt * (steps[-1] if steps else 0)
    creep = abs(centre(steps[-1]) - centre(steps[0])) / duration if duration > 0 else float("nan")
    return judged(["%.3g" % creep], creep <= 1e-6, result)


def overlaps(particles, radii):
    """Largest overlap of two discs as a fraction of the smaller radius."""
    worst, ids = 0.0, sorted(particles)
    for a in range(len(ids)):
        xa, ya = particles[ids[a]]
        for b in range(a + 1, len(ids)):
            xb, yb = particles[ids[b]]
            reach = radii[ids[a]] + radii[ids[b]]
            if abs(xa - xb) < reach and abs(ya - yb) < reach:
                worst = max(worst, (reach - math.hypot(xa - xb, ya - yb)) / min(radii[ids[a]], radii[ids[b]]))
    return worst


def euler_gain(run, scene):
    """Explicit Euler's own energy gain in free fall, ½ Σm |g|² dt t (FORMAT.md), at time t."""
    mass = sum(p["mass"] for p in scene["particles"] if not p.get("pinned"))
    return (lambda t: 0.5 * mass * G * G * run.dt * t) if run.integrator == "euler" else (lambda t: 0.0)


def pile_cell(run, result):
    scene = scene_of(run)
    radii = {i: p["radius"] for i, p in enumerate(scene["particles"])}
    rows = result.rows
    if not rows:
        return judged(["—"] * 4, False, result)
    kinetic0 = sum(0.5 * p["mass"] * (p["velocity"][0] ** 2 + p["velocity"][1] ** 2) for p in scene["particles"])
    late = [s for s in sorted(result.positions) if s * run.dt >= run.steps * run.dt - 1.0 - 1e-9]
    overlap = max(overlaps(result.positions[s], radii) for s in late) if late else float("nan")
    end = rows[-1]["kinetic"] / kinetic0
    gain = euler_gain(run, scene)
    rise = max(r["total_energy"] - rows[0]["total_energy"] - gain(r["t"]) for r in rows)
    gained = max(r["total_energy"] - min(q["total_energy"] for q in rows[:k + 1]) for k, r in enumerate(rows))
    right = overlap <= 0.01 and end <= 1e-4 and rise <= 1e-9 * abs(rows[0]["total_energy"]) and rows[-1]["t"] >= 6 - 1e-9
    values, right = judged(["%.3g %%" % (100 * overlap), "%.3g" % end, g(rise), g(gained)], right, result)
    return values, None if run.variant else right


def seams_cell(run, result):
    left = set()
    for particles in result.positions.values():
        for p, (x, y) in particles.items():
            if max(abs(x), abs(y)) > 1.0 + 1e-9:
                left.add(p)
    return judged(["%d of 40" % len(left)], not left, result)


def ribbon_cell(run, result):
    if run.variant == "no contact":
        return left_out(run, result)
    steps = sorted(result.positions)
    centre = lambda s: sum(p[0] for p in result.positions[s].values()) / len(result.positions[s])
    slid = max(abs(centre(s) - centre(steps[0])) for s in steps) if steps else float("nan")
    return judged(["%.3g" % (1000 * slid)], steps and slid <= 5e-3 and steps[-1] == run.steps, result)


def strand_cell(run, result):
    if run.variant == "no contact":
        return left_out(run, result)
    line = run.variant == "line support"
    reference = strand_discrete_tip({STRAND["corner"]: 1.0}, 14)[0] if line else strand_discrete_tip()[0]
    sink = 0.0
    for particles in result.positions.values():
        for i in range(STRAND["links"]):
            (xa, ya), (xb, yb) = particles[i], particles[i + 1]
            if xa <= 0.0 < xb:
                sink = max(sink, -(ya + (yb - ya) * (0.0 - xa) / (xb - xa)))
    final = result.positions[max(result.positions)] if result.positions else {}
    tip = -final[STRAND["links"]][1] if final else float("nan")
    error = (tip - reference) / reference
    right = sink <= 5e-5 and abs(error) <= 0.05
    values, right = judged(["%.3g" % (1000 * sink) if not line else "(no corner)", "%.2f" % (1000 * tip),
                            "%.2f" % (1000 * reference), "%+.1f %%" % (100 * error)], right, result)
    return values, None if line else right


def free_cradle_cell(run, result):
    mass = CRADLE["mass"]
    final = result.velocities[max(result.velocities)]
    p0, e0 = mass * 1.0, 0.5 * mass * 1.0
    vx, vy = final[4]
    p_error = abs(mass * vx - p0) / p0
    e_error = abs(0.5 * mass * (vx * vx + vy * vy) - e0) / e0
    rest = max(math.hypot(*final[i]) for i in range(4))
    return judged(["%.2g" % p_error, "%.2g" % e_error, "%.2g" % rest],
                  p_error <= 1e-12 and e_error <= 1e-12 and rest <= 1e-12, result)


def hung_cradle_cell(run, result):
    rise = max(particles[9][1] for particles in result.positions.values()) / CRADLE["raise"]
    return judged(["%.4f" % rise], rise >= 0.99, result)


def sleeping_cell(run, result):
    """Before the dropped disc arrives (0.6–0.9 s) the pile is still and asleep; after it (to 2 s)
    the pile has moved and is awake."""
    pile = sum(SLEEP["rows"])
    scene = scene_of(run)
    steps = sorted(result.velocities)
    before = [s for s in steps if 0.6 <= s * run.dt <= 0.9]
    after = [s for s in steps if s * run.dt >= 1.0]
    fastest = max(math.hypot(*result.velocities[s][i]) for s in before for i in range(pile)) if before else float("nan")
    start = {i: scene["particles"][i]["position"] for i in range(pile)}
    moved = max(math.hypot(result.positions[s][i][0] - start[i][0], result.positions[s][i][1] - start[i][1])
                for s in after for i in range(pile)) if after else float("nan")
    if result.rows and "sleeping" in result.rows[0]:
        slept = max(r["sleeping"] for r in result.rows if 0.6 <= r["t"] <= 0.9)
        woke = min(r["sleeping"] for r in result.rows if r["t"] >= 1.0)
        sleep = "%d → %d" % (slept, woke)
        asleep = slept >= pile and woke < pile
    else:
        sleep, asleep = "n/a (no sleeping column)", False
    return judged(["%.3g" % fastest, "%.3g" % (1000 * moved), sleep], fastest <= 1e-6 and moved >= 1e-3 and asleep,
                  result)


def capstan_slip_cell(run, result):
    radius = 0.004 if "discs" in run.scene else 0.0
    return slip_cell(3.0, 0.3, radius, 0.10)(run, result)


CONVERGENCE_NOTE = ("the rows 'convergence' run rk4 at dt/16 and dt/64, not judged: the discrete rope as dt → 0, "
                    "against the closed form (the capstan header gives it with the 20-chord arc's own capstan factor)")


def convergence_runs(scene):
    """rk4 at dt/16 and dt/64 for 1 s: where the discrete rope goes as dt → 0 (not judged)."""
    return [Run(scene, "convergence", "rk4", ROPE["dt"] / k, int(round(k / ROPE["dt"])), int(round(0.02 * k / ROPE["dt"])))
            for k in (16, 64)]


def dt4(dt):
    """The scene's dt and dt/4."""
    return dt, dt / 4


JUDGED = [
    Case("capstan-hold", "Rope of 48 rods over a disc (R 0.3 m, μ 0.3), end masses 0.4 and 0.88 kg (1:2.2 < e^{μπ} = 2.57), "
         "2 s", "the heavy end moves ≤ 1 mm in 2 s", ["rope", "integrator", "dt (s)", "heavy end moved (mm)"],
         lambda: [r for scene in ("capstan-hold.json", "capstan-hold-discs.json")
                  for r in every_integrator(scene, dt4(ROPE["dt"]), 2.0, every=0.02)],
         capstan_hold_cell),
    Case("capstan-slip", "The same rope, end masses 0.4 and 1.2 kg (1:3 > e^{μπ}), 1 s",
         "the heavy end's drop in 1 s within 10% of the closed form with the rope's mass",
         ["rope", "integrator", "dt (s)", "drop (mm)", "closed form (mm)", "error", "max \\|C\\|/L"],
         lambda: [r for scene in ("capstan-slip.json", "capstan-slip-discs.json")
                  for r in every_integrator(scene, dt4(ROPE["dt"]), 1.0, every=0.02)] + convergence_runs("capstan-slip.json"),
         capstan_slip_cell, note=CONVERGENCE_NOTE),
    Case("rope-frictionless", "The same rope over a frictionless disc, end masses 0.4 and 0.48 kg (1:1.2), 1 s",
         "rods within 0.1% (max \\|C\\|/L over the run) and the drop in 1 s within 1% of the closed form with μ 0",
         ["rope", "integrator", "dt (s)", "drop (mm)", "closed form (mm)", "error", "max \\|C\\|/L"],
         lambda: every_integrator("rope-frictionless.json", dt4(ROPE["dt"]), 1.0, every=0.02)
         + convergence_runs("rope-frictionless.json"),
         slip_cell(1.2, 0.0, 0.0, 0.01, rod_limit=1e-3), note=CONVERGENCE_NOTE),
    Case("disc-chains", "Chain of 10 rods (0.1 m) and 1 cm discs: pinned, landing on a floor; free, dropped on a "
         "20° slope (μ 0.5); 3 s", "rods within 2% (max \\|C\\|/L over the run)",
         ["chain", "integrator", "dt (s)", "max \\|C\\|/L", "max energy rise (J)"],
         lambda: every_integrator("disc-chain-floor.json", (0.002,), 3.0, leave_out=("euler",))
         + every_integrator("disc-chain-slope.json", (0.002,), 3.0),
         rod_cell(0.1, 0.02)),
    Case("edge-corners", "A 5 cm spring with a collision edge falling onto a triangle's apex (from 1 mm) and onto "
         "a 4 mm post (from 2 cm), 1 s", "no edge passes a corner (scripts/edge-crossings.py, every step, 32 sub-steps)",
         ["corner", "integrator", "dt (s)", "edges that passed a corner", "lowest end at 1 s (m)"],
         lambda: [r for scene in ("edge-on-apex.json", "edge-on-post.json")
                  for r in every_integrator(scene, (0.001,), 1.0, every=0.001)],
         edge_cell),
    Case("slope-creep", "A 7-rod chain at rest on a 20° slope, μ 0.5 (friction angle 26.6°), 5 s",
         "creep of its centre ≤ 1e-6 m/s", ["chain", "integrator", "dt (s)", "creep (m/s)"],
         lambda: every_integrator("chain-rest-on-slope.json", (0.002,), 5.0, every=0.1), creep_cell),
    Case("disc-pile", "200 discs (r 2.5–3.5 cm) dropped into a box 1 m wide (e 0.2, wall μ 0.5, disc–disc "
         "friction 0.5), 6 s", "rests: overlap ≤ 1% of a radius over the last second, kinetic energy at 6 s ≤ 1e-4 of "
         "the initial (0.45 J), energy never above its start (explicit Euler: above its own free-fall gain ½Σm g² dt t)",
         ["pile", "integrator", "dt (s)", "overlap", "K(6 s)/K(0)", "max E − E(0) (J)", "largest rise above the running minimum (J, not judged)"],
         lambda: every_integrator("disc-pile.json", (0.002,), 6.0, every=0.1)
         + [run._replace(variant="no particleFriction") for run in every_integrator("disc-pile.json", (0.002,), 6.0, every=0.1)],
         pile_cell,
         note="particleFriction is the disc–disc friction coefficient the new solver adds beside particleRestitution; "
              "a reader without it refuses the file (exit 2), and the rows without it show today's pile, not judged"),
    Case("seams-bouncing", "40 particles thrown up (0–0.5 m/s) and along (0.5–3 m/s) the floor of a box of four "
         "touching slabs (floor and ceiling the full width; walls the full height), e 0.9, μ 0.3, 20 s",
         "0 particles leave the box", ["box", "integrator", "dt (s)", "particles that left"],
         lambda: [r for scene in ("box-of-slabs-bouncing.json", "box-of-slabs-bouncing-walls.json")
                  for r in every_integrator(scene, (0.005,), 20.0, every=0.005)], seams_cell),
    Case("ribbon", "A symmetric ribbon of 2 × 31 particles (springs, collision edges) draped over a disc "
         "(R 0.1 m, μ 0.5), 5 s", "its centre slides sideways ≤ 5 mm in 5 s",
         ["ribbon", "integrator", "dt (s)", "largest sideways slide (mm)"],
         lambda: every_integrator("ribbon-over-disc.json", dt4(0.002), 5.0, every=0.02,
                                  leave_out=("euler", ("midpoint", 0.002))),
         ribbon_cell),
    Case("strand-ledge", "A strand of 30 rods (5 cm) with angle springs and collision edges over a frictionless "
         "box ledge, pinned 1.025 m back, 0.475 m past the corner, 2 s",
         "the link over the corner sinks ≤ 0.05 mm below it, and the tip's drop at 2 s within 5% of the "
         "small-deflection model", ["strand", "integrator", "dt (s)", "link sinks (mm)", "tip drop (mm)",
                                    "model (mm)", "error"],
         lambda: every_integrator("strand-over-ledge.json", (STRAND["dt"],), 2.0, every=0.002, leave_out=("euler", "midpoint"))
         + [Run("strand-over-ledge.json", "line support", i, STRAND["dt"], 5000, 5)
            for i in ("symplectic-euler", "rk4", "implicit-euler", "xpbd")],
         strand_cell,
         note="the rows 'line support' hold the strand at its particle 20 by a line constraint instead of the corner "
              "(no corner contact), against the same model with that support: a check of the model on today's engine"),
    Case("cradle-free", "Free Newton's cradle: 5 discs, the first at 1 m/s, no gravity, 0.05 s",
         "the last disc's momentum and energy within 1e-12 of the first's, the others at rest (≤ 1e-12 m/s)",
         ["cradle", "integrator", "dt (s)", "\\|Δp\\|/p", "\\|ΔE\\|/E", "fastest of the others (m/s)"],
         lambda: every_integrator("cradle-free.json", (0.001,), 0.05, every=0.05), free_cradle_cell),
    Case("cradle-hung", "Hung Newton's cradle: 5 discs on 0.5 m rods, the first raised 5 cm, 1 s",
         "the last disc rises ≥ 0.99 h (under rk4, and under every scheme whose own damping of the pendulum "
         "leaves it that)", ["cradle", "integrator", "dt (s)", "rise / h"],
         lambda: every_integrator("cradle-hung.json", (0.001,), 1.0, every=0.001), hung_cradle_cell),
    Case("sleeping-pile", "A pile of 26 discs at rest, a disc thrown up above it falls onto it at 0.93 s, 2 s",
         "the pile still (≤ 1e-6 m/s) and asleep (sleeping ≥ 26) at 0.6–0.9 s, awake (sleeping < 26) and moved "
         "(≥ 1 mm) after the impact", ["pile", "integrator", "dt (s)", "fastest pile disc 0.6–0.9 s (m/s)",
                                      "pile moved after 1 s (mm)", "sleeping before → after"],
         lambda: every_integrator("sleeping-pile.json", (0.002,), 2.0, every=0.01), sleeping_cell,
         note="the sleeping column of particle-lab's CSV (islands and sleep): n/a while the engine has none"),
]

def capstan_header():
    """The closed form's checks: massless and frictionless limits, RK4 convergence, holding."""
    print("\n### Capstan closed form with the rope's mass (docstring)\n")
    e = math.exp(0.3 * math.pi)
    for ratio in (2.2, 3.0):
        rope = rope_of(ratio, 0.3)
        massless = rope._replace(density=1e-15)
        limit = G * (rope.heavy - rope.light * e) / (rope.heavy + rope.light * e)
        print("- 1:%g, μ 0.3: a(0) with ρ → 0 is %.12g m/s², the massless capstan g(M2 − M1e^{μπ})/(M2 + M1e^{μπ}) "
              "%.12g; with the rope's mass %.6g m/s²; holds at rest: %s"
              % (ratio, capstan_acceleration(massless, 0, 0), limit, capstan_acceleration(rope, 0, 0),
                 "yes" if capstan_holds(rope) else "no"))
    rope = rope_of(1.2, 0.0)
    atwood = G * (rope.heavy - rope.light) / (rope.heavy + rope.light + rope.density * (2 * rope.light_hang + math.pi * rope.radius))
    print("- 1:1.2, μ 0: a(0) = %.12g m/s², Atwood's machine with its rope %.12g" % (capstan_acceleration(rope, 0, 0), atwood))
    for label, rope in (("1:3, μ 0.3, points", rope_of(3.0, 0.3)), ("1:3, μ 0.3, 4 mm discs", rope_of(3.0, 0.3, 0.004)),
                        ("1:1.2, μ 0", rope_of(1.2, 0.0))):
        drops = [capstan_drop(rope, 1.0, h)[0] for h in (1e-3, 5e-4, 2.5e-4)]
        s, u = capstan_drop(rope, 1.0)
        print("- %s: s(1 s) = %.12g m at h = 1e-3, changes %.1e and %.1e m at h/2 and h/4; u(1 s) = %.4g m/s; "
              "least N on the arc then %.3g N/rad; light side left hanging %.3g m; with the 20-chord arc's capstan "
              "factor s(1 s) = %.4g m"
              % (label, drops[0], drops[1] - drops[0], drops[2] - drops[0], u, capstan_least_normal_force(rope, s, u),
                 rope.light_hang - s, capstan_drop(rope, 1.0, polygon_factor=polygon_capstan_factor(rope.mu))[0]))
    print("- the 20-chord arc's capstan factor %.6g against e^{μπ} = %.6g" % (polygon_capstan_factor(0.3), e))


def strand_header():
    drop, contact = strand_discrete_tip()
    continuum = strand_continuum_tip()
    b = (STRAND["links"] - STRAND["corner"] - 0.5) * STRAND["rod"]
    print("\n### Strand over a ledge: the small-deflection model (docstring)\n")
    print("- continuum (√2/12 + 1/8) w b⁴/EI = %.4g mm (b %.3g m, w %.4g N/m, EI %.4g N·m²); lift-off √2 b = %.3g m"
          % (1000 * continuum, b, STRAND["mass"] * G / STRAND["rod"], STRAND["stiffness"] * STRAND["rod"], math.sqrt(2) * b))
    print("- the scene's 31 particles: %.4g mm (%+.1f %% from the continuum), resting on the top up to particle %d "
          "(%.3g m before the corner); the runs are judged against it" %
          (1000 * drop, 100 * (drop - continuum) / continuum, contact, (STRAND["corner"] - contact + 0.5) * STRAND["rod"]))


HEADERS = {"capstan-slip": capstan_header, "strand-ledge": strand_header}


def execute(runner, case_runs):
    """Runs every (case, run) pair in one pool: {(case name, run): Result}."""
    paths = {}
    for _, run in case_runs:
        key = (run.scene, run.variant)
        if key not in paths:
            paths[key] = runner.scene(scene_of(run))
    with concurrent.futures.ThreadPoolExecutor(runner.jobs) as pool:
        futures = {(case.name, run): pool.submit(runner.result, paths[(run.scene, run.variant)], run.integrator, run.dt,
                                                 run.steps, run.every) for case, run in case_runs}
        return {key: f.result() for key, f in futures.items()}


def report(case, results):
    """Prints a case's table; returns True when every judged row is right."""
    if case.name in HEADERS:
        HEADERS[case.name]()
    print("\n### %s\n\nCriterion: %s.%s\n" % (case.title, case.criterion, (" Note: " + case.note + ".") if case.note else ""))
    print("| " + " | ".join(case.header + ["stopped", "verdict"]) + " |")
    print("|" + " --- |" * (len(case.header) + 2))
    verdicts = []
    for run in case.plan():
        result = results[(case.name, run)]
        values, verdict = case.cell(run, result)
        if verdict is None:
            word = "not judged"
        else:
            word = "right" if verdict else "wrong"
            verdicts.append(verdict)
        label = run.scene.replace(".json", "") + (" (%s)" % run.variant if run.variant else "")
        values = list(values) + [""] * (len(case.header) - 3 - len(values))
        print("| " + " | ".join([label, run.integrator, "%g" % run.dt] + values + [failure(result) or "—", word]) + " |")
    right = bool(verdicts) and all(verdicts)
    print("\n**%s: %s** (%d of %d runs right)" % (case.name, "right" if right else "wrong", sum(verdicts), len(verdicts)))
    return right


def write_scenes():
    for name, build in SCENES.items():
        with open(os.path.join(DATA, name), "w") as f:
            f.write(scene_text(build()))
    with open(os.path.join(DATA, "references.json"), "w") as f:
        f.write(reference_text())
    print("wrote %d scene files and references.json to %s" % (len(SCENES), os.path.relpath(DATA, ROOT)))


def check_scenes():
    """Exit 1 (one line per file) when a file in DATA is not what its builder writes."""
    stale = []
    for name, text in [(n, scene_text(b())) for n, b in SCENES.items()] + [("references.json", reference_text())]:
        path = os.path.join(DATA, name)
        if not os.path.exists(path) or open(path).read() != text:
            stale.append(name)
    for name in stale:
        print("contact-cases: tests/data/contacts/%s differs from its builder (run --write-scenes)" % name)
    if stale:
        sys.exit(1)
    print("contact-cases: %d scene files and references.json match their builders" % len(SCENES))

CASES = {"chain-floor": chain_on_floor, "chain-slope": chain_on_slope, "wire": wire_and_floor,
         "friction": friction, "dopri5": dopri5_bounce, "capsule": capsule, "seams": seams, "wedge": wedge}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--lab", default=os.path.join(ROOT, "build", "demos", "particle-lab"))
    parser.add_argument("--jobs", type=int, default=len(os.sched_getaffinity(0)))
    parser.add_argument("--write-scenes", action="store_true",
                        help="write the judged cases' scene files and references.json to tests/data/contacts and exit")
    parser.add_argument("--check-scenes", action="store_true",
                        help="exit 1 when a file in tests/data/contacts differs from its builder")
    judged_names = [case.name for case in JUDGED]
    parser.add_argument("cases", nargs="*", metavar="CASE", help="any of: " + ", ".join(list(CASES) + judged_names))
    args = parser.parse_args()
    if args.write_scenes:
        return write_scenes()
    if args.check_scenes:
        return check_scenes()
    unknown = [c for c in args.cases if c not in CASES and c not in judged_names]
    if unknown:
        sys.exit("contact-cases: unknown case %s (known: %s)" % (unknown[0], ", ".join(list(CASES) + judged_names)))
    if not os.access(args.lab, os.X_OK):
        sys.exit("contact-cases: %s is not an executable; build it or pass --lab" % args.lab)
    chosen = args.cases or list(CASES) + judged_names
    with tempfile.TemporaryDirectory() as work:
        runner = Runner(args.lab, work, max(1, args.jobs))
        for name in chosen:
            if name in CASES:
                CASES[name](runner)
        cases = [case for case in JUDGED if case.name in chosen]
        results = execute(runner, [(case, run) for case in cases for run in case.plan()])
        verdicts = [report(case, results) for case in cases]
    if verdicts:
        print("\n**%d judged cases: %d right, %d wrong** (%s)" % (len(verdicts), sum(verdicts), len(verdicts) - sum(verdicts),
              ", ".join("%s %s" % (c.name, "right" if v else "wrong") for c, v in zip(cases, verdicts))))


if __name__ == "__main__":
    main()
