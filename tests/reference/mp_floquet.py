#!/usr/bin/python3
"""Independent reference for the balanced state's Floquet multipliers on an anisotropic
support (docs/model.md §10.6), to compare with `stability-scan equilibria --format json`.

How it differs from the C++ route (Hill's method in long double, Magnus-4 cross-check):
  * the support force is written from the fixed frame, F = -R^T (K_f R q + C_f R (q' + omega J2 q)),
    R = R(omega t), and differentiated at each t (no harmonic decomposition);
  * the ball rows and the mass matrix come from tests/reference/mp_reference.py (the
    project's 80-digit isotropic reference) at the mean support;
  * the monodromy is integrated over pi/omega by the 3-stage Radau IIA collocation (order 5,
    L-stable, so the stiff coulomb ball rates decay as they should) at 30 digits, with m and
    2m steps; the run fails if the two differ by more than 1e-11 relative on a multiplier
    of modulus >= 1e-6;
  * multipliers are the eigenvalues of the mp monodromy (mp.eig).

Usage: mp_floquet.py SCENE.toml [--steps M] [--json CPP.json --rtol 1e-8]
Two balls, [[ball]] tables. Exits 1 if the C++ multipliers differ by more than rtol
(relative, multipliers with |rho| >= 1e-6; smaller ones: absolute 1e-9).
"""
import argparse
import json
import os
import sys
import tomllib

from mpmath import mp, mpf

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mp_reference as ref  # noqa: E402

DPS = 30


def load(path):
    with open(path, "rb") as f:
        t = tomllib.load(f)
    r, fr = t["rotor"], t["friction"]
    K = (float(r["stiffness_x"]), float(r["stiffness_y"]), float(r.get("stiffness_xy", 0.0)))
    C = (float(r["damping_x"]), float(r["damping_y"]), float(r.get("damping_xy", 0.0)))
    rolling = t.get("rolling", True)
    balls = []
    for b in t["ball"]:
        kw = {k: b.get(k, fr.get(k)) for k in ("mu", "d", "mu_c", "mu_s", "v_s")}
        balls.append(ref.Ball(b["mass"], b["race_radius"], b["radius"], b.get("rolling", rolling), **kw))
    omega = float(t["speed"]["omega"])
    p = ref.Params(r["mass"], (K[0] + K[1]) / 2, (C[0] + C[1]) / 2, r["unbalance"], omega, balls, fr["law"],
                   fr.get("kappa"), path)
    return p, K, C


def sym(a, b, ab):
    return mp.matrix([[mpf(a), mpf(ab)], [mpf(ab), mpf(b)]])


def jacobian_at(p, K, C, state, t):
    """J(t) at the balanced state: model.md §6 at the mean support, the rotor block replaced by
    the derivative of the fixed-frame support force (linear in q, q')."""
    w = mpf(p.omega)
    Gs, Gv = ref.db_ds_dsdot(p, state)
    R = mp.matrix([[mp.cos(w * t), -mp.sin(w * t)], [mp.sin(w * t), mp.cos(w * t)]])
    J2 = mp.matrix([[0, -1], [1, 0]])
    Kr = R.T * sym(*K) * R
    Cr = R.T * sym(*C) * R
    kbar, cbar = (mpf(K[0]) + mpf(K[1])) / 2, (mpf(C[0]) + mpf(C[1])) / 2
    dFdq = -Kr - w * Cr * J2 - (-kbar * mp.eye(2) - w * cbar * J2)   # minus the mean already in Gs
    dFdv = -Cr + cbar * mp.eye(2)
    for i in range(2):
        for j in range(2):
            Gs[i, j] += dFdq[i, j]
            Gv[i, j] += dFdv[i, j]
    Ainv = mp.inverse(ref.mass_matrix(p, state[2], state[3]))
    P, Q = Ainv * Gs, Ainv * Gv
    J = mp.zeros(8, 8)
    for r in range(4):
        J[r, 4 + r] = 1
        for c in range(4):
            J[4 + r, c] = P[r, c]
            J[4 + r, 4 + c] = Q[r, c]
    return J


def radau_monodromy(Jof, T, m):
    s6 = mp.sqrt(6)
    c = [(4 - s6) / 10, (4 + s6) / 10, mpf(1)]
    A = [[(88 - 7 * s6) / 360, (296 - 169 * s6) / 1800, (-2 + 3 * s6) / 225],
         [(296 + 169 * s6) / 1800, (88 + 7 * s6) / 360, (-2 - 3 * s6) / 225],
         [(16 - s6) / 36, (16 + s6) / 36, mpf(1) / 9]]
    h = T / m
    n = 8
    Phi = mp.eye(n)
    for k in range(m):
        t0 = k * h
        Js = [Jof(t0 + ci * h) for ci in c]
        M = mp.eye(3 * n)
        for i in range(3):
            for j in range(3):
                for r in range(n):
                    for q in range(n):
                        M[i * n + r, j * n + q] -= h * A[i][j] * Js[j][r, q]
        rhs = mp.zeros(3 * n, n)
        for i in range(3):
            for r in range(n):
                for q in range(n):
                    rhs[i * n + r, q] = Phi[r, q]
        Y = mp.inverse(M) * rhs
        Phi = mp.matrix([[Y[2 * n + r, q] for q in range(n)] for r in range(n)])
    return Phi


def multipliers(Phi):
    ev = mp.eig(Phi, left=False, right=False)
    return sorted(ev, key=lambda z: (-abs(z), -z.imag))


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--json")
    ap.add_argument("--rtol", type=float, default=1e-8)
    ap.add_argument("--states", type=int, default=1, help="balanced states to check (default 1: the second is the "
                    "first with the balls swapped, for equal balls)")
    a = ap.parse_args(argv)
    mp.dps = DPS
    p, K, C = load(a.scene)
    T = mp.pi / mpf(p.omega)
    cpp = json.load(open(a.json))["balanced_states"] if a.json else None
    bal = ref._balanced(p)
    if cpp is not None and len(cpp) != len(bal):
        print(f"FAIL: {len(cpp)} balanced states from the program, {len(bal)} here")
        return 1
    bad = 0
    for idx, e in enumerate(bal[:a.states]):
        with mp.workdps(40):
            e = ref.newton_polish(p, e) or e
        state = [mpf(0), mpf(0), mpf(e.b1), mpf(e.b2)]
        Jof = lambda t: jacobian_at(p, K, C, state, t)  # noqa: E731
        rho1 = multipliers(radau_monodromy(Jof, T, a.steps))
        rho2 = multipliers(radau_monodromy(Jof, T, 2 * a.steps))
        conv = max(min(abs(x - y) for x in rho1) / abs(y) for y in rho2 if abs(y) >= 1e-6)
        print(f"balanced {idx + 1}: beta = {mp.nstr(e.b1, 12)} {mp.nstr(e.b2, 12)}; Radau {a.steps} vs "
              f"{2 * a.steps} steps: {mp.nstr(conv, 3)}")
        if conv > 1e-11:
            print("FAIL: the reference itself is not converged")
            bad += 1
        for z in rho2:
            print(f"  |rho| = {mp.nstr(abs(z), 15)}  arg = {mp.nstr(mp.arg(z), 15)}")
        if cpp is not None:
            got = [complex(x, y) for x, y in cpp[idx]["floquet_multipliers"]]
            want = [complex(z) for z in rho2]
            for g in got:
                w = min(want, key=lambda z: abs(z - g))
                err = abs(g - w) / abs(w) if abs(w) >= 1e-6 else abs(g - w)
                tol = a.rtol if abs(w) >= 1e-6 else 1e-9
                flag = "ok" if err <= tol else "FAIL"
                bad += flag == "FAIL"
                print(f"  program {g:.15g}: {flag} ({err:.2g})")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
