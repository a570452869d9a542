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

Usage: composed_orbit_reference.py SCENE.toml --json EQUILIBRIA.json [--tol 1e-6]
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


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("--json", required=True)
    ap.add_argument("--tol", type=float, default=1e-6)
    a = ap.parse_args(argv)
    with open(a.scene, "rb") as fh:
        scene = tomllib.load(fh)
    with open(a.json) as fh:
        got = json.load(fh)
    w = float(scene["speed"]["omega"])
    n, Mf, rf = equations(scene)
    d = 2 * n + 4
    rot, balls = scene["rotor"], scene_balls(scene)
    M = rot["mass"] + sum(b["mass"] for b in balls)
    L = (rot["unbalance"] + sum(b["mass"] * b["race_radius"] for b in balls)) / M
    scale = np.array([L, L] + [1.0] * n + [L * w, L * w] + [w] * n)
    T = math.pi / w

    def f(t, x):  # the rotating-frame field from the fixed-frame Lagrangian
        th = w * t
        c, s = math.cos(th), math.sin(th)
        q, dq = x[0:2], x[n + 2:n + 4]
        Z = [c * q[0] - s * q[1], s * q[0] + c * q[1]]
        v = [dq[0] - w * q[1], dq[1] + w * q[0]]  # q' + omega J2 q
        dZ = [c * v[0] - s * v[1], s * v[0] + c * v[1]]
        y = [*Z, *x[2:n + 2], *dZ, *x[n + 4:]]
        args = [*y, th, w, 0.0]
        acc = np.linalg.solve(np.array(Mf(*args), float), np.array(rf(*args), float))
        ddq = [c * acc[0] + s * acc[1] + 2 * w * dq[1] + w * w * q[0],
               -s * acc[0] + c * acc[1] - 2 * w * dq[0] + w * w * q[1]]
        return np.concatenate([x[n + 2:], ddq, acc[2:]])

    def flow(x0):
        sol = solve_ivp(f, (0, T), x0, method="DOP853", rtol=1e-13, atol=1e-15)
        if not sol.success:
            raise RuntimeError(sol.message)
        return sol.y[:, -1]

    def monodromy(x0):
        P = np.zeros((d, d))
        for j in range(d):
            h = 1e-6 * scale[j]
            e = np.zeros(d)
            e[j] = h
            P[:, j] = (flow(x0 + e) - flow(x0 - e)) / (2 * h)
        return P

    worst = 0.0
    orbits = got["periodic_orbits"]
    for o in orbits:
        if o["status"] != "converged":
            print(f"{o['kind']}: not converged in the C++ run ({o['reason']})")
            return 1
        x = np.array(o["state0"], float)
        for it in range(8):  # Newton on phi(T; x) - x = 0, to a residual of 1e-12 (scaled)
            r = flow(x) - x
            if np.max(np.abs(r / scale)) <= 1e-12:
                break
            x = x + np.linalg.solve(monodromy(x) - np.eye(d), -r)
        else:
            print(f"{o['kind']}: the reference's shooting did not converge")
            return 2
        P = monodromy(x)
        rho = sorted(np.linalg.eigvals(P), key=lambda z: (-abs(z), -np.angle(z)))
        mine = sorted((complex(re, im) for re, im in o["floquet_multipliers"]), key=lambda z: (-abs(z), -np.angle(z)))
        dx0 = float(np.max(np.abs((x - np.array(o["state0"])) / scale)))
        drho = max(abs(p - m) / max(abs(p), 1e-6) for p, m in zip(rho, mine))
        worst = max(worst, dx0, drho)
        print(f"{o['kind']}: x(0) differs by {dx0:.3g} (scaled), multipliers by {drho:.3g}; max |rho| {abs(rho[0]):.9f}")
    print(f"{len(orbits)} orbits, largest difference {worst:.3g} (tolerance {a.tol:g})")
    return 0 if orbits and worst <= a.tol else 1


if __name__ == "__main__":
    sys.exit(main())
