#!/usr/bin/python3
"""Independent reference for `simulate` on a rigid rotor with an unround race and an
anisotropic support at once (docs/model.md §20), constant speed or a linear ramp from t = 0.

How it differs from the C++ route (the rotating-frame equations (20.1): the unround race's
A and b of (11.3.3)-(11.3.4) written out by hand, plus the support's force (10.14.1), GSL's
integrators with the analytic Jacobian):
  * the equations come from the Lagrangian written in the FIXED frame by sympy: the rotor
    centre Z = (X, Y) fixed, the rotor's centre of mass at Z + R(theta) (U / M_r, 0), ball i's
    centre at Z + R(theta) p_i(beta_i) with p_i = l_i(beta) e^{i beta} of (11.1.1)-(11.1.2),
    the ball's spin theta' - s_i' beta_i' / r_i (rolling on the race, j_i = 1 + I / (m r^2)),
    the support's potential Z^T K_f Z / 2 and its damping force -C_f Z' in the fixed frame (no
    decomposition into mean and turning parts), viscous rolling resistance -d_i s_i'^2 beta_i'
    (model.md (4.3) along the path); M(q) q'' = rhs by sympy's derivatives of L;
  * integration by scipy's DOP853 at rtol 1e-12;
  * the rotating-frame state is recovered as q = R(theta)^T Z at each sample of the CSV.
Exit 0 if every sample of the CSV agrees within --tol (q scaled by the displacement scale
L = (U + sum m_i l_i) / M, angles in rad); 1 on a mismatch; 2 on bad input.

Usage: composed_simulation_reference.py SCENE.toml --csv simulation.csv [--ramp W0:W1:A] [--tol 1e-7]
"""
import argparse
import math
import sys
import tomllib

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp


def scene_balls(scene):
    if "ball" in scene:
        return scene["ball"]
    ring = scene["balls"]
    return [dict(ring) for _ in range(ring["count"])]


def harmonics(scene, balls):
    race = scene.get("race", {})
    out = []
    for i, b in enumerate(balls):
        spec, surface = race.get("unroundness"), False
        if "surface_unroundness" in race:
            spec, surface = race["surface_unroundness"], True
        for pb in race.get("ball", []):
            if pb["ball"] == i + 1:
                for key in ("unroundness", "surface_unroundness"):
                    if key in pb:
                        spec, surface = pb[key], key.startswith("surface")
        l, r = b["race_radius"], b["radius"]
        conv = (l + r) / l if surface else 1.0
        out.append([(h["order"], h["amplitude"] * conv, h.get("phase", 0.0)) for h in (spec or [])])
    return out


def path_radius(h, l, beta):
    """(11.1.1)-(11.1.2): the exactly offset circle times 1 + sum_{k>=2} eps cos(k beta - phi)."""
    e, f = l, 1
    for k, eps, phi in h:
        if k == 1:
            d = l * eps
            e = d * sp.cos(beta - phi) + sp.sqrt(l * l - d * d * sp.sin(beta - phi) ** 2)
        else:
            f += eps * sp.cos(k * beta - phi)
    return e * f


def equations(scene, module="math"):
    """(n, M, rhs): M(q, q', theta, Omega, Omega') q'' = rhs, lambdified for `module` ("math" for
    one state, "numpy" for arrays of states at once)."""
    balls = scene_balls(scene)
    n = len(balls)
    rot, fr = scene["rotor"], scene["friction"]
    if fr["law"] != "viscous":
        raise ValueError("the reference handles the viscous law")
    if "stiffness_x" in rot:
        K = [[rot["stiffness_x"], rot.get("stiffness_xy", 0.0)], [rot.get("stiffness_xy", 0.0), rot["stiffness_y"]]]
        C = [[rot["damping_x"], rot.get("damping_xy", 0.0)], [rot.get("damping_xy", 0.0), rot["damping_y"]]]
    else:
        K = [[rot["stiffness"], 0.0], [0.0, rot["stiffness"]]]
        C = [[rot["damping"], 0.0], [0.0, rot["damping"]]]
    Mr, U = rot["mass"], rot["unbalance"]
    rolling = scene.get("rolling", True)
    H = harmonics(scene, balls)
    X, Y, th, Om = sp.symbols("X Y theta Omega", real=True)
    beta = sp.symbols(f"b0:{n}", real=True)
    dX, dY = sp.symbols("dX dY", real=True)
    dbeta = sp.symbols(f"db0:{n}", real=True)
    q, dq = [X, Y, *beta], [dX, dY, *dbeta]
    e = lambda a: (sp.cos(a), sp.sin(a))
    c, s = e(th)
    # velocity of a point Z + R(theta) (a, b)(t): Z' + R'(theta) theta' (a, b) + R(theta) (a', b')
    def velocity(a, b, da, db):
        return (dX + Om * (-s * a - c * b) + c * da - s * db, dY + Om * (c * a - s * b) + s * da + c * db)
    vx, vy = velocity(U / Mr, 0, 0, 0)
    T = Mr * (vx**2 + vy**2) / 2
    D = 0  # Rayleigh's function of the friction
    for i, b in enumerate(balls):
        m, l, r = b["mass"], b["race_radius"], b["radius"]
        j = 1.4 if b.get("rolling", rolling) else 1.0
        ell = path_radius(H[i], l, beta[i])
        px, py = ell * sp.cos(beta[i]), ell * sp.sin(beta[i])
        dpx, dpy = sp.diff(px, beta[i]), sp.diff(py, beta[i])
        vx, vy = velocity(px, py, dpx * dbeta[i], dpy * dbeta[i])
        speed = sp.sqrt(dpx**2 + dpy**2)
        T += m * (vx**2 + vy**2) / 2 + (j - 1) * m * (r * Om - speed * dbeta[i]) ** 2 / 2
        D += b.get("d", fr.get("d", 0.0)) * speed**2 * dbeta[i] ** 2 / 2
    V = (K[0][0] * X**2 + 2 * K[0][1] * X * Y + K[1][1] * Y**2) / 2
    D += (C[0][0] * dX**2 + 2 * C[0][1] * dX * dY + C[1][1] * dY**2) / 2
    L = T - V
    dOm = sp.symbols("dOmega", real=True)
    pL = [sp.diff(L, v) for v in dq]
    M = sp.Matrix([[sp.diff(pl, v) for v in dq] for pl in pL])
    # d/dt dL/dq' = M q'' + sum_j d2L/dq'dq_j q_j' + d2L/dq'dtheta Omega + d2L/dq'dOmega Omega'
    rhs = sp.Matrix([sp.diff(L, qi) - sp.diff(D, dqi) - sum(sp.diff(pl, qj) * dqj for qj, dqj in zip(q, dq))
                     - sp.diff(pl, th) * Om - sp.diff(pl, Om) * dOm for qi, dqi, pl in zip(q, dq, pL)])
    args = [*q, *dq, th, Om, dOm]
    return n, sp.lambdify(args, M.tolist(), module, cse=True), sp.lambdify(args, list(rhs), module, cse=True)


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("--csv", required=True)
    ap.add_argument("--ramp", help="W0:W1:ALPHA, as simulate's --ramp")
    ap.add_argument("--tol", type=float, default=1e-7)
    a = ap.parse_args(argv)
    with open(a.scene, "rb") as fh:
        scene = tomllib.load(fh)
    if a.ramp:
        w0, w1, alpha = map(float, a.ramp.split(":"))
        alpha = math.copysign(abs(alpha), w1 - w0)
        t1 = (w1 - w0) / alpha
    else:
        w0 = w1 = float(scene["speed"]["omega"])
        alpha, t1 = 0.0, 0.0

    def speed(t):  # omega, omega', theta
        if t < t1:
            return w0 + alpha * t, alpha, w0 * t + alpha * t * t / 2
        return w1, 0.0, w0 * t1 + alpha * t1 * t1 / 2 + w1 * (t - t1)

    n, Mf, rf = equations(scene)
    with open(a.csv) as fh:
        rows = [line.rstrip("\n").split(",") for line in fh if not line.startswith("#")]
    header, rows = rows[0], rows[1:]
    data = {name: np.array([float(r[k]) if r[k] else math.nan for r in rows]) for k, name in enumerate(header)}
    t = data["t"]
    cols = ["q1", "q2"] + [f"beta{i + 1}" for i in range(n)] + ["dq1", "dq2"] + [f"dbeta{i + 1}" for i in range(n)]
    x0 = np.array([data[cname][0] for cname in cols])
    # the start in the fixed frame: Z = R(0) q, Z' = q' + omega J2 q at theta = 0
    w, _, _ = speed(0.0)
    y0 = np.concatenate([[x0[0], x0[1]], x0[2:n + 2], [x0[n + 2] - w * x0[1], x0[n + 3] + w * x0[0]], x0[n + 4:]])

    def f(tt, y):
        om, dom, th = speed(tt)
        args = [*y, th, om, dom]
        acc = np.linalg.solve(np.array(Mf(*args), float), np.array(rf(*args), float).ravel())
        return np.concatenate([y[n + 2:], acc])

    breaks = [0.0] + ([t1] if 0 < t1 < t[-1] else []) + [t[-1]]
    ys = []
    y = y0
    for a0, a1 in zip(breaks[:-1], breaks[1:]):
        sel = t[(t >= a0) & (t <= a1)]
        sol = solve_ivp(f, (a0, a1), y, method="DOP853", rtol=1e-12, atol=1e-14, t_eval=sel, dense_output=True)
        if not sol.success:
            print("reference integration failed:", sol.message)
            return 2
        for k, tk in enumerate(sel):
            if not ys or tk > ys[-1][0]:
                ys.append((tk, sol.y[:, k]))
        y = sol.sol(a1)
    rot, balls = scene["rotor"], scene_balls(scene)
    M = rot["mass"] + sum(b["mass"] for b in balls)
    Lq = (rot["unbalance"] + sum(b["mass"] * b["race_radius"] for b in balls)) / M
    worst = 0.0
    for k, (tk, yk) in enumerate(ys):
        _, _, th = speed(tk)
        c, s = math.cos(th), math.sin(th)
        q1, q2 = c * yk[0] + s * yk[1], -s * yk[0] + c * yk[1]
        err = max(abs(q1 - data["q1"][k]) / Lq, abs(q2 - data["q2"][k]) / Lq,
                  *(abs(yk[2 + i] - data[f"beta{i + 1}"][k]) for i in range(n)))
        worst = max(worst, err)
    print(f"{len(ys)} samples to t = {t[-1]:g} s, largest scaled difference {worst:.3g} (tolerance {a.tol:g})")
    return 0 if worst <= a.tol else 1


if __name__ == "__main__":
    sys.exit(main())
