#!/usr/bin/python3
"""Independent reference for the periodic states of an unround race on an anisotropic support
(docs/model.md §20.4): each pi/omega-periodic orbit of `stability-scan equilibria SCENE --format
json` ("periodic_orbits") found again and its 2n + 4 Floquet multipliers computed again.

How it differs from the C++ route (multiple shooting over pi/omega with Radau IIA steps on the
rotating-frame field (20.1), continued in the anisotropy delta from the race's equilibria,
multipliers from the product of the transition matrices):
  * the field is the fixed-frame Lagrangian of composed_simulation_reference.py (sympy), mapped
    to the rotating frame (q = R(theta)^T Z, q'' = R^T Z'' - 2 omega J2 q' + omega^2 q);
  * SINGLE shooting: Newton on x0 with phi(pi/omega; x0) - x0 = 0 from the C++ x(0), the flow by
    scipy's DOP853 at rtol 1e-13, its Jacobian (the monodromy) by central differences of the
    flow (steps 1e-6 of each variable's scale);
  * multipliers: eigenvalues of that monodromy (numpy).
Exit 0 if every orbit converges and its x(0) (scaled) and every multiplier agree within --tol;
1 on a mismatch; 2 on bad input or a reference that did not converge.

With --sweep, the same for the orbits a `sweep --param omega` wrote (sweep_omega.csv: x(0) and
the multipliers of every converged orbit) at --values of its values (docs/model.md §20.6).

Usage: composed_orbit_reference.py SCENE.toml --json EQUILIBRIA.json [--tol 1e-6]
       composed_orbit_reference.py SCENE.toml --sweep sweep_omega.csv [--values 3] [--tol 1e-6]
"""
import argparse
import json
import math
import os
import sys
import tomllib

import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from composed_simulation_reference import equations, scene_balls  # noqa: E402


class Shooting:
    """Single shooting over pi/omega on the fixed-frame Lagrangian's field at one omega."""

    def __init__(self, n, Mf, rf, L, w):
        self.n, self.d, self.w, self.T = n, 2 * n + 4, w, math.pi / w
        self.Mf, self.rf = Mf, rf
        self.scale = np.array([L, L] + [1.0] * n + [L * w, L * w] + [w] * n)

    def f(self, t, x):  # the rotating-frame field from the fixed-frame Lagrangian
        n, w = self.n, self.w
        th = w * t
        c, s = math.cos(th), math.sin(th)
        q, dq = x[0:2], x[n + 2:n + 4]
        Z = [c * q[0] - s * q[1], s * q[0] + c * q[1]]
        v = [dq[0] - w * q[1], dq[1] + w * q[0]]  # q' + omega J2 q
        dZ = [c * v[0] - s * v[1], s * v[0] + c * v[1]]
        y = [*Z, *x[2:n + 2], *dZ, *x[n + 4:]]
        args = [*y, th, w, 0.0]
        acc = np.linalg.solve(np.array(self.Mf(*args), float), np.array(self.rf(*args), float))
        ddq = [c * acc[0] + s * acc[1] + 2 * w * dq[1] + w * w * q[0],
               -s * acc[0] + c * acc[1] - 2 * w * dq[0] + w * w * q[1]]
        return np.concatenate([x[n + 2:], ddq, acc[2:]])

    def flow(self, x0):
        sol = solve_ivp(self.f, (0, self.T), x0, method="DOP853", rtol=1e-13, atol=1e-15)
        if not sol.success:
            raise RuntimeError(sol.message)
        return sol.y[:, -1]

    def monodromy(self, x0):
        P = np.zeros((self.d, self.d))
        for j in range(self.d):
            h = 1e-6 * self.scale[j]
            e = np.zeros(self.d)
            e[j] = h
            P[:, j] = (self.flow(x0 + e) - self.flow(x0 - e)) / (2 * h)
        return P

    def check(self, label, state0, multipliers):
        """Newton from the C++ x(0); returns the largest difference (x(0) scaled, multipliers
        relative to max(|rho|, 1e-6)), or None if the reference's shooting did not converge."""
        x = np.array(state0, float)
        for it in range(8):  # Newton on phi(T; x) - x = 0, to a residual of 1e-12 (scaled)
            r = self.flow(x) - x
            if np.max(np.abs(r / self.scale)) <= 1e-12:
                break
            x = x + np.linalg.solve(self.monodromy(x) - np.eye(self.d), -r)
        else:
            print(f"{label}: the reference's shooting did not converge")
            return None
        P = self.monodromy(x)
        rho = sorted(np.linalg.eigvals(P), key=lambda z: (-abs(z), -np.angle(z)))
        mine = sorted(multipliers, key=lambda z: (-abs(z), -np.angle(z)))
        dx0 = float(np.max(np.abs((x - np.array(state0)) / self.scale)))
        drho = max(abs(p - m) / max(abs(p), 1e-6) for p, m in zip(rho, mine))
        print(f"{label}: x(0) differs by {dx0:.3g} (scaled), multipliers by {drho:.3g}; max |rho| {abs(rho[0]):.9f}")
        return max(dx0, drho)


def sweep_orbits(path, count):
    """The converged orbits of a `sweep --param omega` CSV at `count` of its values (the first,
    the last and evenly between): [(omega, label, x(0), multipliers)]."""
    with open(path) as fh:
        lines = [ln for ln in fh.read().splitlines() if ln and not ln.startswith("#")]
    head = lines[0].split(",")
    if head[0] != "omega":
        raise ValueError(f"{path}: a sweep over omega is checked (got {head[0]})")
    rows = [dict(zip(head, ln.split(","))) for ln in lines[1:]]
    values = sorted({float(r["omega"]) for r in rows})
    pick = {values[round(i * (len(values) - 1) / max(count - 1, 1))] for i in range(min(count, len(values)))}
    d = sum(1 for h in head if h.startswith("x0_"))
    out = []
    for r in rows:
        if float(r["omega"]) not in pick or r["status"] != "converged":
            continue
        mult = [complex(float(r[f"mult_re{k}"]), float(r[f"mult_im{k}"])) for k in range(1, d + 1)]
        x0 = [float(r[f"x0_{k}"]) for k in range(1, d + 1)]
        out.append((float(r["omega"]), f"omega={r['omega']} orbit {r['track']}", x0, mult))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    src = ap.add_mutually_exclusive_group(required=True)
    src.add_argument("--json", help="`equilibria --format json` output: its periodic_orbits")
    src.add_argument("--sweep", help="`sweep --param omega` CSV (sweep_omega.csv): the orbits at --values of its values")
    ap.add_argument("--values", type=int, default=3, help="how many of the sweep's values to check (default 3)")
    ap.add_argument("--tol", type=float, default=1e-6)
    a = ap.parse_args(argv)
    with open(a.scene, "rb") as fh:
        scene = tomllib.load(fh)
    n, Mf, rf = equations(scene)
    rot, balls = scene["rotor"], scene_balls(scene)
    M = rot["mass"] + sum(b["mass"] for b in balls)
    L = (rot["unbalance"] + sum(b["mass"] * b["race_radius"] for b in balls)) / M
    if a.json:
        with open(a.json) as fh:
            got = json.load(fh)
        w = float(scene["speed"]["omega"])
        orbits = []
        for o in got["periodic_orbits"]:
            if o["status"] != "converged":
                print(f"{o['kind']}: not converged in the C++ run ({o['reason']})")
                return 1
            orbits.append((w, o["kind"], o["state0"], [complex(re, im) for re, im in o["floquet_multipliers"]]))
    else:
        orbits = sweep_orbits(a.sweep, a.values)
    worst = 0.0
    shooting = {}
    for w, label, x0, mult in orbits:
        if w not in shooting:
            shooting[w] = Shooting(n, Mf, rf, L, w)
        diff = shooting[w].check(label, x0, mult)
        if diff is None:
            return 2
        worst = max(worst, diff)
    print(f"{len(orbits)} orbits, largest difference {worst:.3g} (tolerance {a.tol:g})")
    return 0 if orbits and worst <= a.tol else 1


if __name__ == "__main__":
    sys.exit(main())
