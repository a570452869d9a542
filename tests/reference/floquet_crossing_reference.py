#!/usr/bin/python3
"""Independent check of the Floquet crossings a `stability-scan sweep --param omega` reports on
an anisotropic support (docs/model.md §10.11): at each located speed omega*, a balanced state's
largest multiplier has |rho| = 1, and it is on opposite sides of 1 just below and above omega*.

How it differs from the C++ route (Magnus-4 / Hill on J0 + cos Jc + sin Js, bisection):
  * J(t) comes from mp_floquet.py's jacobian_at: the fixed-frame support force differentiated at
    each t, with the ball rows and mass matrix of the 80-digit isotropic reference
    (mp_reference.py), the balanced state Newton-polished there;
  * its three harmonics are read off at t = 0, T/2, T/4 (T = pi/omega) and the decomposition is
    checked at t = T/7 (relative 1e-12), then the monodromy is integrated in double by scipy's
    DOP853 (rtol 1e-12) on the SI state (no scaling), and rho = numpy.linalg.eigvals.

Usage: floquet_crossing_reference.py SCENE.toml CROSSINGS.csv [--tol 1e-8] [--delta 1e-4]
Exits 1 if a crossing's |ln max|rho|| exceeds tol (for the best-matching balanced state), if the
sign does not change over omega* (1 -+ delta), or if the file has no crossing.
"""
import argparse
import csv
import os
import sys

import numpy as np
from mpmath import mp, mpf
from scipy.integrate import solve_ivp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mp_floquet as mf  # noqa: E402
import mp_reference as ref  # noqa: E402


def harmonics(p, K, C, state):
    T = mp.pi / mpf(p.omega)
    J_0 = mf.jacobian_at(p, K, C, state, mpf(0))
    J_half = mf.jacobian_at(p, K, C, state, T / 2)
    J_quarter = mf.jacobian_at(p, K, C, state, T / 4)
    J0 = (J_0 + J_half) / 2
    Jc = (J_0 - J_half) / 2
    Js = J_quarter - J0
    t = T / 7
    w = mpf(p.omega)
    check = mf.jacobian_at(p, K, C, state, t) - (J0 + mp.cos(2 * w * t) * Jc + mp.sin(2 * w * t) * Js)
    scale = mp.mnorm(J0, 1)
    if mp.mnorm(check, 1) > 1e-12 * scale:
        raise SystemExit(f"FAIL: J(t) is not J0 + cos Jc + sin Js ({mp.nstr(mp.mnorm(check, 1) / scale, 3)})")
    to_np = lambda M: np.array(M.tolist(), dtype=float)  # noqa: E731
    return to_np(J0), to_np(Jc), to_np(Js)


def log_max_modulus(p, K, C, omega):
    """ln max|rho| of every balanced state at this speed."""
    p.omega = float(omega)
    out = []
    for e in ref._balanced(p):
        with mp.workdps(40):
            e = ref.newton_polish(p, e) or e
        J0, Jc, Js = harmonics(p, K, C, [mpf(0), mpf(0), mpf(e.b1), mpf(e.b2)])
        n = J0.shape[0]
        w = p.omega

        def rhs(t, y):
            return ((J0 + np.cos(2 * w * t) * Jc + np.sin(2 * w * t) * Js) @ y.reshape(n, n)).ravel()

        sol = solve_ivp(rhs, (0.0, np.pi / w), np.eye(n).ravel(), method="DOP853", rtol=1e-12, atol=1e-14)
        rho = np.linalg.eigvals(sol.y[:, -1].reshape(n, n))
        out.append(float(np.log(np.max(np.abs(rho)))))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("crossings")
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--delta", type=float, default=1e-4)
    a = ap.parse_args(argv)
    mp.dps = 30
    p, K, C = mf.load(a.scene)
    with open(a.crossings) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    if not rows:
        print("FAIL: no crossing in", a.crossings)
        return 1
    bad = 0
    for r in rows:
        w = float(r["omega"])
        at = log_max_modulus(p, K, C, w)
        k = min(range(len(at)), key=lambda i: abs(at[i]))
        below = log_max_modulus(p, K, C, w * (1 - a.delta))[k]
        above = log_max_modulus(p, K, C, w * (1 + a.delta))[k]
        ok = abs(at[k]) <= a.tol and below * above < 0
        bad += not ok
        print(f"{r['kind']} of balanced {r['member']} at omega* = {w!r}: reference ln max|rho| = {at[k]:.3e} "
              f"(tol {a.tol:g}); at omega*(1 -+ {a.delta:g}): {below:.3e}, {above:.3e}: {'ok' if ok else 'FAIL'}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
