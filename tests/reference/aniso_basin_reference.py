#!/usr/bin/python3
"""Independent reference for `stability-scan basin` on an anisotropic support (docs/model.md §15.5,
§20): every cell integrated again from its start in the FIXED frame (the sympy Lagrangian of
composed_simulation_reference.py: the support's K_f and C_f acting on the fixed-frame centre, no
mean/turning decomposition), all cells at once by scipy's DOP853 at rtol 1e-9, and classified here.

The scene (not one of data/): two unequal viscous balls on a support 9000/7000 N/m with a cross
term, at 350 rad/s (about 1.5 times the support's frequencies) where both mirror balanced states
are stable by their Floquet multipliers, and at 150 rad/s where both are unstable.

Asserted at 350 rad/s, per cell (3 x 3 grid):
  1. the program's end state (t_end of the cell: the settle test's stop) equals the reference's
     there: q / L and beta to 1e-5 (both integrations are accurate to ~1e-8 of the motion; the
     settling motion does not amplify their differences, 1e-5 leaves room for the program's rtol
     1e-8 accumulated over ~10^3 turns);
  2. the reference's end state lies within the settle radius (1e-2, scaled as §15.5) of the balanced
     state the program names (member = its place in `equilibria`'s list) and outside it of the
     other: the classification is the physics', not the program's integrator's.
At 150 rad/s: the settle test knows no attractor (the provenance says "none stable", and
`equilibria` calls both balanced states unstable); every cell is judged at t_end by §15.2
(periodic or not_settled), none by the settle test.

usage: aniso_basin_reference.py BINARY
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import tomllib

import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from composed_simulation_reference import equations  # noqa: E402

EXE = sys.argv[1]
SCENE = """[rotor]
mass = 0.15
stiffness_x = 9000.0
stiffness_y = 7000.0
stiffness_xy = 500.0
damping_x = 12.0
damping_y = 9.0
damping_xy = 1.5
unbalance = 6.0e-7
[[ball]]
mass = 3.5e-5
race_radius = 0.019
radius = 1.0e-3
[[ball]]
mass = 3.0e-5
race_radius = 0.02
radius = 1.2e-3
[friction]
law = "viscous"
d = 5.0e-4
[speed]
omega = {omega}
"""
RADIUS = 1e-2  # the basin's default settle radius (model.md §15.5)
failures = []


def run(*args):
    r = subprocess.run([EXE, *args], capture_output=True, text=True)
    if r.returncode != 0:
        failures.append(f"{' '.join(args)}: exit {r.returncode}\n{r.stderr}")
    return r


def basin_rows(path):
    with open(path) as f:
        lines = f.read().splitlines()
    comments = [x for x in lines if x.startswith("#")]
    return comments, list(csv.DictReader(x for x in lines if not x.startswith("#")))


def reference_ends(scene, omega, starts, t_ends):
    """Every cell from rest (q = q' = 0, beta' = 0) to its t_end; rotating-frame (q1, q2, beta, q', beta')."""
    n, mass, force = equations(scene, "numpy")
    cells = len(starts)
    y0 = np.zeros((2 * (n + 2), cells))
    y0[2:2 + n] = np.array(starts).T

    def field(t, flat):
        y = flat.reshape(2 * (n + 2), cells)
        args = [*y, omega * t, omega, 0.0]
        full = lambda v: np.broadcast_to(np.asarray(v, float), (cells,))
        A = np.array([[full(v) for v in row] for row in mass(*args)]).transpose(2, 0, 1)
        b = np.array([full(v) for v in force(*args)]).T[..., None]
        return np.concatenate([y[n + 2:], np.linalg.solve(A, b)[..., 0].T]).ravel()

    sol = solve_ivp(field, (0.0, max(t_ends)), y0.ravel(), method="DOP853", rtol=1e-9, atol=1e-12, dense_output=True)
    if not sol.success:
        raise RuntimeError(f"reference integration failed: {sol.message}")
    ends = []
    for k, t in enumerate(t_ends):
        y = sol.sol(t).reshape(2 * (n + 2), cells)[:, k]
        c, s = math.cos(omega * t), math.sin(omega * t)
        q1, q2 = c * y[0] + s * y[1], -s * y[0] + c * y[1]
        # q' in the rotating frame: R^T Z' - omega J q
        dq1 = c * y[n + 2] + s * y[n + 3] + omega * q2
        dq2 = -s * y[n + 2] + c * y[n + 3] - omega * q1
        ends.append((q1, q2, list(y[2:2 + n]), dq1, dq2, list(y[n + 4:])))
    return ends


def scaled_distance(end, beta, L, omega):
    q1, q2, b, dq1, dq2, db = end
    d = max(abs(q1) / L, abs(q2) / L, abs(dq1) / (L * omega), abs(dq2) / (L * omega))
    d = max(d, *(abs(v) / omega for v in db))
    return max(d, *(abs(math.remainder(x - y, 2 * math.pi)) for x, y in zip(b, beta)))


with tempfile.TemporaryDirectory() as tmp:
    for omega in (350.0, 150.0):
        path = f"{tmp}/s{int(omega)}.toml"
        with open(path, "w") as f:
            f.write(SCENE.format(omega=omega))
        with open(path, "rb") as f:
            scene = tomllib.load(f)
        states = json.loads(run("equilibria", path, "--format", "json").stdout)["balanced_states"]
        stable = [s for s in states if s["stability"] == "stable"]
        run("basin", path, "--grid", "3", "--t-end", "30", "--threads", "2", "--no-chart", "-o", f"{tmp}/b{int(omega)}")
        if failures:
            break
        comments, rows = basin_rows(f"{tmp}/b{int(omega)}/basin.csv")
        line = next((c for c in comments if c.startswith("# attractors of the settle test")), "")
        named = line.split(": ", 1)[-1]
        expected = ", ".join(f"balanced {s['member']}" for s in stable) or "none stable"
        if named != expected:
            failures.append(f"omega={omega}: attractors '{named}', equilibria's stable balanced states '{expected}'")
        if not stable:
            for r in rows:
                if r["by_settle_test"] != "0" or r["attractor"] not in ("periodic", "not_settled"):
                    failures.append(f"omega={omega} cell ({r['i']}, {r['j']}): {r['attractor']} "
                                    f"(by_settle_test {r['by_settle_test']}) with no stable balanced state")
            continue
        balls = scene["ball"]
        L = (scene["rotor"]["unbalance"] + sum(b["mass"] * b["race_radius"] for b in balls)) / (
            scene["rotor"]["mass"] + sum(b["mass"] for b in balls))
        starts = [[float(r["beta1_0"]), float(r["beta2_0"])] for r in rows]
        ends = reference_ends(scene, omega, starts, [float(r["t_end"]) for r in rows])
        worst = 0.0
        for r, end in zip(rows, ends):
            where = f"omega={omega} cell ({r['i']}, {r['j']})"
            program = [float(r["beta1_end"]), float(r["beta2_end"])]
            diff = max(abs(math.remainder(x - y, 2 * math.pi)) for x, y in zip(program, end[2]))
            diff = max(diff, abs(float(r["q_abs_end"]) - math.hypot(end[0], end[1])) / L)
            worst = max(worst, diff)
            if diff > 1e-5:
                failures.append(f"{where}: end state differs from the reference's by {diff:.3g} (scaled)")
            if r["attractor"] != "balanced":
                failures.append(f"{where}: {r['attractor']}, but every start here settles on a balanced state")
                continue
            near = [s["member"] for s in stable if scaled_distance(end, s["beta"], L, omega) <= RADIUS]
            if near != [int(r["member"])]:
                failures.append(f"{where}: the program says balanced {r['member']}, the reference's end lies within "
                                f"the settle radius of {near}")
        print(f"omega={omega}: {len(rows)} cells, largest end-state difference {worst:.3g} (scaled)")

if failures:
    print("\n".join(failures))
    sys.exit(1)
print("basin on an anisotropic support: every cell's end and attractor agree with the fixed-frame reference")
