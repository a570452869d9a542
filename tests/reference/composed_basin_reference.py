#!/usr/bin/python3
"""Independent reference for `stability-scan basin` on an unround race with an anisotropic support
(docs/model.md §20.8): no state is at rest there, the attractors are the race's states as
pi/omega-periodic orbits, and the settle test compares a run with the orbit's state at the run's
own spin angle. Every cell is integrated again from its start in the FIXED frame (the sympy
Lagrangian of composed_simulation_reference.py: the support's K_f and C_f on the fixed-frame
centre, each ball on its path), all cells at once by scipy's DOP853 at rtol 1e-9; each stable
orbit is integrated here from the state at theta = 0 that `equilibria --format json` gives.

The scene (not one of data/ or tests/scenes): two unequal viscous balls on a race with an offset
centre and a third harmonic, a support 3000/16000 N/m with a cross term (strongly anisotropic, so
that an orbit's state moves over its period by 4-5 % of L in q and twice that in q' / (L omega):
more than the settle radius, a wrong phase misses the orbit); at 400 rad/s `equilibria` finds six
orbits, two of them stable. The speed program: a run-up 330 -> 400 rad/s at 1000 rad/s^2, then the
hold, so that the spin angle after the run-up is 400 t - 2.45 rad: the phase the settle test uses
is the profile's angle, not omega t (with omega t every cell misses its orbit: checked by hand).

Asserted per cell (3 x 3 grid):
  1. the program's end state equals the reference's at the cell's t_end: q / L and beta to 1e-5
     (both integrations are accurate to ~1e-8 of the motion over the ~10^3 turns);
  2. the cell is `orbit k` by the settle test, k a stable orbit of `equilibria`, and the
     reference's end state lies within the settle radius (1e-2, scaled as §15.5: q / L, angles,
     q' / (L omega), beta' / omega; + 1e-4 for the two measurements' differences) of orbit k's
     state at the same spin angle and outside it of every other stable orbit: the
     classification, phase included, is the physics'.
Also: the header's attractor line names exactly the stable orbits of `equilibria`.

usage: composed_basin_reference.py BINARY
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
from shaft_simulation_reference import Speed  # noqa: E402  (omega(t), omega'(t), theta(t) of a ramp and hold)

EXE = sys.argv[1]
SCENE = """[rotor]
mass = 0.18
stiffness_x = 3000.0
stiffness_y = 16000.0
stiffness_xy = 600.0
damping_x = 3.0
damping_y = 5.0
damping_xy = 0.4
unbalance = 1.0e-6
[[ball]]
mass = 5.0e-5
race_radius = 0.018
radius = 1.1e-3
[[ball]]
mass = 4.0e-5
race_radius = 0.019
radius = 1.0e-3
[friction]
law = "viscous"
d = 3.0e-4
[speed]
omega = 400.0
[race]
unroundness = [{ order = 1, amplitude = 3e-5, phase = 0.3 }, { order = 3, amplitude = 1.5e-5, phase = -0.7 }]
"""
OMEGA = 400.0
RAMP = (330.0, 400.0, 1000.0)  # omega0, omega1 [rad/s], alpha [rad/s^2]
RADIUS = 1e-2  # the basin's default settle radius (model.md §15.5)
# A cell stops at the sample where the program's distance has been <= RADIUS five times; here the
# same distance is measured by other means: the program's interpolation between 128 samples
# ((pi/128)^2 / 8 = 7.5e-5 of the orbit's variation, ~0.1 scaled in q') and the two integrations
# (~1e-7) may put it up to ~1e-5 beyond. The other stable orbit lies O(1) away (ball angles).
SLACK = 1e-4
failures = []


def run(*args):
    r = subprocess.run([EXE, *args], capture_output=True, text=True)
    if r.returncode != 0:
        failures.append(f"{' '.join(args)}: exit {r.returncode}\n{r.stderr}")
    return r


def integrate(scene, speed, y0, t_ends):
    """Fixed-frame states (Z, beta, Z', beta') of every column of y0 at its own t_end, as rotating-frame
    rows (q1, q2, beta.., q1', q2', beta'..)."""
    n, mass, force = equations(scene, "numpy")
    cells = y0.shape[1]

    def field(t, flat):
        y = flat.reshape(2 * (n + 2), cells)
        args = [*y, speed.theta(t), speed.omega(t), speed.omega_dot(t)]
        full = lambda v: np.broadcast_to(np.asarray(v, float), (cells,))
        A = np.array([[full(v) for v in row] for row in mass(*args)]).transpose(2, 0, 1)
        b = np.array([full(v) for v in force(*args)]).T[..., None]
        return np.concatenate([y[n + 2:], np.linalg.solve(A, b)[..., 0].T]).ravel()

    # The ramp's end is a kink of omega(t): integrate the two pieces apart.
    pieces, start, y = [], 0.0, y0.ravel()
    for stop in sorted({t for t in (speed.t1, max(t_ends)) if t > 0}):
        sol = solve_ivp(field, (start, stop), y, method="DOP853", rtol=1e-9, atol=1e-12, dense_output=True)
        if not sol.success:
            raise RuntimeError(f"reference integration failed: {sol.message}")
        pieces.append((start, stop, sol.sol))
        start, y = stop, sol.y[:, -1]
    out = []
    for k, t in enumerate(t_ends):
        sol = next(s for a, b, s in pieces if a <= t <= b)
        y = sol(t).reshape(2 * (n + 2), cells)[:, k]
        th, w = speed.theta(t), speed.omega(t)
        c, s = math.cos(th), math.sin(th)
        q1, q2 = c * y[0] + s * y[1], -s * y[0] + c * y[1]
        dq1 = c * y[n + 2] + s * y[n + 3] + w * q2  # q' = R^T Z' - omega J q
        dq2 = -s * y[n + 2] + c * y[n + 3] - w * q1
        out.append(np.array([q1, q2, *y[2:2 + n], dq1, dq2, *y[n + 4:]]))
    return out


def fixed_from_rotating(x, n, omega):
    """A rotating-frame state at theta = 0 as the fixed frame's: Z = q, Z' = q' + omega J q."""
    y = np.array(x, float)
    y[n + 2], y[n + 3] = x[n + 2] - omega * x[1], x[n + 3] + omega * x[0]
    return y


def scaled_distance(a, b, n, L, omega):
    d = max(abs(a[k] - b[k]) / L for k in (0, 1))
    d = max(d, *(abs(a[n + 2 + k] - b[n + 2 + k]) / (L * omega) for k in (0, 1)))
    d = max(d, *(abs(math.remainder(a[2 + k] - b[2 + k], 2 * math.pi)) for k in range(n)))
    return max(d, *(abs(a[n + 4 + k] - b[n + 4 + k]) / omega for k in range(n)))


with tempfile.TemporaryDirectory() as tmp:
    path = f"{tmp}/scene.toml"
    with open(path, "w") as f:
        f.write(SCENE)
    with open(path, "rb") as f:
        scene = tomllib.load(f)
    n = len(scene["ball"])
    orbits = json.loads(run("equilibria", path, "--format", "json").stdout)["periodic_orbits"]
    stable = {k + 1: o for k, o in enumerate(orbits) if o["stability"] == "stable"}
    if len(stable) < 2:
        failures.append(f"expected two stable orbits at {OMEGA} rad/s, equilibria gives {list(stable)}")
    balls = scene["ball"]
    L = (scene["rotor"]["unbalance"] + sum(b["mass"] * b["race_radius"] for b in balls)) / (
        scene["rotor"]["mass"] + sum(b["mass"] for b in balls))
    period = math.pi / OMEGA
    # The run-up only: its phase at the end is the profile's angle, not omega t (a constant speed
    # is the special case; tests/test_composed_basin.cpp checks the orbit's phase there).
    for name, speed, extra in (("ramp", Speed(*RAMP), ["--ramp", ":".join(f"{v:g}" for v in RAMP)]),):
        if failures:
            break
        out = f"{tmp}/{name}"
        run("basin", path, "--grid", "3", "--t-end", "30", "--threads", "2", "--no-chart", "-o", out, *extra)
        if failures:
            break
        with open(f"{out}/basin.csv") as f:
            lines = f.read().splitlines()
        named = next((c for c in lines if c.startswith("# attractors of the settle test")), "").split(": ", 1)[-1]
        expected = ", ".join(f"orbit {k}" for k in stable)
        if named != expected:
            failures.append(f"{name}: attractors '{named}', the stable orbits of equilibria '{expected}'")
        rows = list(csv.DictReader(x for x in lines if not x.startswith("#")))
        starts = np.zeros((2 * (n + 2), len(rows)))
        for c, r in enumerate(rows):
            starts[2:2 + n, c] = [float(r["beta1_0"]), float(r["beta2_0"])]
        ends = integrate(scene, speed, starts, [float(r["t_end"]) for r in rows])
        # Each stable orbit from its state at theta = 0, at constant omega: its state at the phase
        # of every cell's end, theta(t_end) mod pi.
        phases = [(speed.theta(float(r["t_end"])) % math.pi) / OMEGA for r in rows]
        on_orbit = {}
        for k, o in stable.items():
            y0 = np.tile(fixed_from_rotating(o["state0"], n, OMEGA)[:, None], (1, len(rows)))
            on_orbit[k] = integrate(scene, Speed(OMEGA), y0, phases) if max(phases) > 0 else None
            # the orbit closes: one period from x(0) returns to it
            back = integrate(scene, Speed(OMEGA), y0[:, :1], [period])[0]
            gap = scaled_distance(back, o["state0"], n, L, OMEGA)
            if gap > 1e-7:
                failures.append(f"orbit {k}: the reference's run over one period ends {gap:.3g} from x(0)")
        worst_end, worst_orbit = 0.0, 0.0
        for c, (r, end) in enumerate(zip(rows, ends)):
            where = f"{name} cell ({r['i']}, {r['j']})"
            program = [float(r["beta1_end"]), float(r["beta2_end"])]
            diff = max(abs(math.remainder(x - y, 2 * math.pi)) for x, y in zip(program, end[2:2 + n]))
            diff = max(diff, abs(float(r["q_abs_end"]) - math.hypot(end[0], end[1])) / L)
            worst_end = max(worst_end, diff)
            if diff > 1e-5:
                failures.append(f"{where}: end state differs from the reference's by {diff:.3g} (scaled)")
            if r["attractor"] != "orbit" or r["by_settle_test"] != "2":
                failures.append(f"{where}: {r['attractor']} (by_settle_test {r['by_settle_test']}), expected a "
                                "stable orbit by the settle test")
                continue
            near = [k for k in stable if scaled_distance(end, on_orbit[k][c], n, L, OMEGA) <= RADIUS + SLACK]
            worst_orbit = max(worst_orbit, scaled_distance(end, on_orbit[int(r["member"])][c], n, L, OMEGA))
            if near != [int(r["member"])]:
                failures.append(f"{where}: the program says orbit {r['member']}, the reference's end lies within the "
                                f"settle radius of the orbits {near} at its spin angle")
        members = sorted({r["member"] for r in rows})
        print(f"{name}: {len(rows)} cells on orbits {members}; largest end-state difference {worst_end:.3g}, "
              f"largest distance to the named orbit {worst_orbit:.3g} (scaled, radius {RADIUS})")

if failures:
    print("\n".join(failures))
    sys.exit(1)
print("basin on an unround race with an anisotropic support: every cell's end and orbit agree with the "
      "fixed-frame reference")
