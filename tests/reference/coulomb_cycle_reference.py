#!/usr/bin/python3
"""Independent reference for one coulomb limit cycle of `stability-scan continue --cycles`
(docs/model.md §17.11-§17.13): the period, the two slow Floquet multipliers (the trivial
one and the one that decides stability) and Liouville's sum of all eight ln|mu|.

    coulomb_cycle_reference.py SCENE CYCLES_CSV [--row K] [--rtol 1e-6]

The orbit at the parameter of row K (default: the last) is recomputed by single
shooting: Newton on (x0, T) with phi(x0, T) - x0 = 0 and the phase condition
(x0 - g) . f(g) = 0, g the C++ orbit's x0 (the start guess only). The flow and its
monodromy matrix come from scipy's Radau (implicit, L-stable: the ball modes of 5.7e4 1/s
and the rotor's of 8.3 1/s are stiff on an orbit of 2225 s) on the field of model.md
(3.7)-(3.10) written again in numpy (cycle_reference.Field), its Jacobian by the complex
step. Single shooting is well conditioned here: every multiplier but the two slow ones
is below 1e-8000. The slow multipliers are the two largest eigenvalues of the monodromy
(the others are rounding); ln|mu| summed over all eight must equal the integral of trace J
over the orbit (Liouville), integrated with the orbit. Self-check: the reference at
tolerances 1e-10 and 1e-11 must agree to 1e-8 relative, else exit 2. Nothing of the C++
code is used.
Exit 0: every quantity within rtol; 1: a mismatch; 2: bad input or no convergence.
"""
import argparse
import math
import os
import sys

import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mp_reference as ref  # noqa: E402  (the scene reader)
from cycle_reference import Field, load_orbit, orbit_start  # noqa: E402  (the numpy field of model.md (3.10))


def jacobian(f, x):
    X = np.tile(np.asarray(x, dtype=complex), (8, 1))
    for k in range(8):
        X[k, k] += 1e-30j
    return (f(X).imag / 1e-30).T


def flow(f, D, x0, T, tol):
    """Scaled y = x / D over [0, T]: y(T), the monodromy (SI), integral of trace J."""
    Dinv = 1.0 / D

    def rhs(t, z):
        y = z[:8]
        x = y * D
        fx = f(x[None, :].astype(complex))[0].real
        J = jacobian(f, x)
        Js = (Dinv[:, None] * J) * D[None, :]
        P = z[8:72].reshape(8, 8)
        return np.concatenate([fx * Dinv, (Js @ P).ravel(), [np.trace(J)]])

    def jac(t, z):
        x = z[:8] * D
        Js = (Dinv[:, None] * jacobian(f, x)) * D[None, :]
        out = np.zeros((73, 73))
        out[:8, :8] = Js
        out[8:72, 8:72] = np.kron(Js, np.eye(8))  # d(Js P)/dP, P row-major
        return out

    z0 = np.concatenate([np.asarray(x0) * Dinv, np.eye(8).ravel(), [0.0]])
    s = solve_ivp(rhs, (0.0, T), z0, method="Radau", jac=jac, rtol=tol, atol=tol)
    if not s.success:
        raise RuntimeError(f"Radau failed: {s.message}")
    z = s.y[:, -1]
    Ps = z[8:72].reshape(8, 8)
    Phi = (D[:, None] * Ps) * Dinv[None, :]
    return z[:8] * D, Phi, z[72]


def orbit(f, D, guess, T0, tol):
    g = np.asarray(guess, dtype=float)
    fg = f(g[None, :].astype(complex))[0].real / D
    fg = fg / np.linalg.norm(fg)
    y, T = g / D, float(T0)
    for it in range(10):
        xT, Phi, tr = flow(f, D, y * D, T, tol)
        r = np.concatenate([xT / D - y, [(y - g / D) @ fg]])
        fT = f(xT[None, :].astype(complex))[0].real / D
        Jm = np.zeros((9, 9))
        Jm[:8, :8] = (Phi / D[:, None]) * D[None, :] - np.eye(8)
        Jm[:8, 8] = fT
        Jm[8, :8] = fg
        dz = np.linalg.solve(Jm, -r)
        y += dz[:8]
        T += dz[8]
        size = max(np.max(np.abs(dz[:8])), abs(dz[8]) / T)
        if size < 1e3 * tol:
            xT, Phi, tr = flow(f, D, y * D, T, tol)
            mult = np.linalg.eigvals(Phi)
            mult = sorted(mult, key=lambda m: -abs(m))
            return T, mult[:2], tr
    raise RuntimeError("the reference Newton did not converge")


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("cycles_csv")
    ap.add_argument("--row", type=int, default=-1)
    ap.add_argument("--rtol", type=float, default=1e-6)
    a = ap.parse_args(argv)
    try:
        row, param, f = load_orbit(a.scene, a.cycles_csv, a.row)
    except (ref.InputError, OSError, StopIteration, IndexError) as e:
        print(f"coulomb_cycle_reference: {e}", file=sys.stderr)
        return 2
    guess = orbit_start(row)
    T_cpp = float(row["period"])
    mu_cpp = [complex(float(row[f"mult_re{k}"]), float(row[f"mult_im{k}"])) for k in range(1, 3)]
    logsum_cpp = sum(float(row[f"mult_logmod{k}"]) for k in range(1, 9))
    wH = 2 * math.pi / T_cpp
    L = (f.U + sum(f.ml)) / f.M
    D = np.array([L, L, 1, 1, L * wH, L * wH, wH, wH])
    try:
        runs = [orbit(f, D, guess, T_cpp, tol) for tol in (1e-10, 1e-11)]
    except (RuntimeError, np.linalg.LinAlgError) as e:
        print(f"coulomb_cycle_reference: {e}", file=sys.stderr)
        return 2
    (T1, m1, tr1), (T2, m2, tr2) = runs
    self_err = max(abs(T1 - T2) / T2, abs(tr1 - tr2) / abs(tr2), *(abs(x - y) / abs(y) for x, y in zip(m1, m2)))
    print(f"{param} = {row[param]}: Radau at 1e-10 and 1e-11; self-check {self_err:.2e}")
    if self_err > 1e-8:
        print("coulomb_cycle_reference: the reference did not converge in its tolerance", file=sys.stderr)
        return 2
    checks = [("period", T_cpp, T2), ("mult1", mu_cpp[0], m2[0]), ("mult2", mu_cpp[1], m2[1]),
              ("sum ln|mu| vs int tr J", logsum_cpp, tr2)]
    worst = 0.0
    for name, got, want in checks:
        rel = abs(got - want) / abs(want)
        worst = max(worst, rel)
        print(f"  {name:24s} analyzer {got:.15g}  reference {want:.15g}  relative {rel:.2e}")
    if worst > a.rtol:
        print(f"coulomb_cycle_reference: FAILED: worst relative difference {worst:.2e} > {a.rtol:g}", file=sys.stderr)
        return 1
    print(f"ok: worst relative difference {worst:.2e} <= {a.rtol:g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
