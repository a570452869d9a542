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
step, in the scaled state x / D of model.md §17.2. Single shooting is well conditioned
here: every multiplier but the two slow ones is below 1e-8000. The slow multipliers are
the two largest eigenvalues of the monodromy (the others are rounding); ln|mu| summed over
all eight must equal the integral of trace J over the orbit (Liouville), taken by the
periodic trapezoid rule on 4096 samples of the converged orbit's dense output.

Tolerances (rtol = atol on the scaled state): 1e-8 and 3e-9, not tighter. At 1e-9 and
below scipy's Radau stalls: the rounding of the rotor's force balance (w^2 U against
m l w^2 cos(beta) ~ 0.04 N, i.e. ~2e-9 1/s in the scaled dq / (L w_H)) keeps its simplified
Newton's corrections above its acceptance (~sqrt(rtol) (atol + rtol |y|) ~ 2e-15 at
1e-10), every step fails and is halved down to ~2e-5 s: some 1e8 steps per period, days
of CPU (model.md §17.15). What each run costs is the monodromy's identity start: the
rotor pair it excites in the columns is resolved until it has decayed (~2 s, ~2e4 steps).
So each Newton step flows the monodromy once and then only the state (~100 steps) from the
corrected (x0, T): that residual must be below 100 tol and the correction below 1e-4
(scaled), else another step. The multipliers are those of that last monodromy (one
correction of at most 1e-4 before the accepted orbit; the self-check sees its effect).
Self-check: the two tolerances must agree to rtol / 10, else exit 2. Nothing of the C++
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


H_CS = 1e-30  # the complex step: exact first derivatives to rounding


def field_and_jacobian(f, x):
    """f(x) and J(x) = df/dx (complex step) from one batched evaluation of nine states."""
    X = np.tile(np.asarray(x, dtype=complex), (9, 1))
    for k in range(8):
        X[1 + k, k] += 1j * H_CS
    F = f(X)
    return F[0].real, (F[1:].imag / H_CS).T


def flow_monodromy(f, D, y0, T, tol):
    """Scaled y = x / D and the scaled monodromy Y(t) over [0, T]: y(T), Y(T).

    The identity start excites the rotor pair (-8.33 +- 499.7i 1/s) in the columns: that
    transient is resolved (some 2 s of the period, ~2e4 steps) and is what this flow costs."""
    Dinv = 1.0 / D

    def rhs(t, z):
        fx, J = field_and_jacobian(f, z[:8] * D)
        Js = (Dinv[:, None] * J) * D[None, :]
        return np.concatenate([fx * Dinv, (Js @ z[8:].reshape(8, 8)).ravel()])

    def jac(t, z):
        _, J = field_and_jacobian(f, z[:8] * D)
        Js = (Dinv[:, None] * J) * D[None, :]
        out = np.zeros((72, 72))
        out[:8, :8] = Js
        out[8:, 8:] = np.kron(Js, np.eye(8))  # d(Js P)/dP, P row-major
        return out

    z0 = np.concatenate([y0, np.eye(8).ravel()])
    s = solve_ivp(rhs, (0.0, T), z0, method="Radau", jac=jac, rtol=tol, atol=tol)
    if not s.success:
        raise RuntimeError(f"Radau failed: {s.message}")
    return s.y[:8, -1], s.y[8:, -1].reshape(8, 8), s.t.size - 1


def flow_state(f, D, y0, T, tol):
    """The state alone (scaled) over [0, T], with its dense output: a few hundred steps."""
    Dinv = 1.0 / D

    def rhs(t, y):
        return f((y * D)[None, :].astype(complex))[0].real * Dinv

    def jac(t, y):
        return (Dinv[:, None] * field_and_jacobian(f, y * D)[1]) * D[None, :]

    s = solve_ivp(rhs, (0.0, T), y0, method="Radau", jac=jac, rtol=tol, atol=tol, dense_output=True)
    if not s.success:
        raise RuntimeError(f"Radau failed: {s.message}")
    return s


def trace_integral(f, D, sol, T, n):
    """int_0^T trace J(x(t)) dt by the periodic trapezoid rule on n samples of the dense
    output (exponentially convergent for a smooth periodic integrand)."""
    X = (sol.sol(T * np.arange(n) / n).T * D).astype(complex)
    tr = np.zeros(n)
    for k in range(8):
        Xk = X.copy()
        Xk[:, k] += 1j * H_CS
        tr += f(Xk)[:, k].imag / H_CS
    return T * tr.mean()


def orbit(f, D, guess, T0, tol, log=None):
    """Single shooting at Radau tolerance tol: (T, the two largest multipliers, int trace J).

    Newton on (y0, T) with the monodromy flow; after each correction the state alone is
    flown from the corrected (y0, T) (cheap) and its residual must have fallen below
    100 tol, else another Newton step. The multipliers are those of the last monodromy,
    taken one correction (below 1e-4 scaled) before the accepted orbit: near the Hopf point
    Phi - I is nearly singular (mu - 1 ~ 4e-7), so a residual of 1e-11 already moves x0 by
    ~1e-6 along the slow directions; the monodromy hardly changes with it."""
    g = np.asarray(guess, dtype=float)
    fg = f(g[None, :].astype(complex))[0].real / D
    fg = fg / np.linalg.norm(fg)
    y, T = g / D, float(T0)
    for it in range(6):
        yT, Phi, steps = flow_monodromy(f, D, y, T, tol)
        r = np.concatenate([yT - y, [(y - g / D) @ fg]])
        fT = f((yT * D)[None, :].astype(complex))[0].real / D
        Jm = np.zeros((9, 9))
        Jm[:8, :8] = Phi - np.eye(8)
        Jm[:8, 8] = fT
        Jm[8, :8] = fg
        dz = np.linalg.solve(Jm, -r)
        y = y + dz[:8]
        T += dz[8]
        size = max(np.max(np.abs(dz[:8])), abs(dz[8]) / T)
        s = flow_state(f, D, y, T, tol)
        r2 = np.max(np.abs(s.y[:, -1] - y))
        if log:
            log(f"  tol {tol:g}: Newton {it + 1}: residual {np.max(np.abs(r)):.2e} -> {r2:.2e} (state-only flow, "
                f"{s.t.size - 1} steps), correction {size:.2e}; monodromy flow {steps} steps")
        if r2 < 100 * tol and size < 1e-4:
            mult = sorted(np.linalg.eigvals(Phi), key=lambda m: -abs(m))
            return T, mult[:2], trace_integral(f, D, s, T, 4096)
    raise RuntimeError("the reference Newton did not converge")


TOLS = (1e-8, 3e-9)  # Radau rtol = atol on the scaled state; at 1e-9 and below it stalls (see above)


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
        runs = [orbit(f, D, guess, T_cpp, tol, log=print) for tol in TOLS]
    except (RuntimeError, np.linalg.LinAlgError) as e:
        print(f"coulomb_cycle_reference: {e}", file=sys.stderr)
        return 2
    (T1, m1, tr1), (T2, m2, tr2) = runs
    self_err = max(abs(T1 - T2) / T2, abs(tr1 - tr2) / abs(tr2), *(abs(x - y) / abs(y) for x, y in zip(m1, m2)))
    print(f"{param} = {row[param]}: Radau at {TOLS[0]:g} and {TOLS[1]:g}; self-check {self_err:.2e}")
    if self_err > a.rtol / 10:
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
