#!/usr/bin/python3
"""Independent reference for one periodic orbit of `stability-scan continue --cycles`
(docs/model.md §17): period, amplitude max|q| and all 8 Floquet multipliers to --rtol.

    cycle_reference.py SCENE CYCLES_CSV [--row K] [--rtol 1e-6] [--steps N]

The orbit at the parameter of row K of the CSV (default: the last one, farthest from the
Hopf point) is recomputed here by single shooting: Newton on (x0, T) with the equations
phi(x0, T) - x0 = 0 and the phase condition (x0 - g) . f(g) = 0, g the C++ orbit's x0 (only
the start guess). The flow is classical RK4 at N fixed steps per period, in numpy, on the
field of model.md (3.7)-(3.10) written here again (scene values through mp_reference's
scene reader); its derivatives by the complex step through the whole integration (the
exact derivative of the discrete flow: nine complex trajectories at once). The result is
checked against 2N steps: the reference itself must agree to 1e-9 relative (period,
amplitude, multipliers), else the script fails (exit 2). Nothing of the C++ code is used.

The multipliers are the eigenvalues of the monodromy matrix itself: for a viscous scene
(the smallest multiplier ~1e-3) its rounding error is far below 1e-6 relative.
Exit 0: every quantity within rtol; 1: a mismatch; 2: bad input or a reference that did
not converge.
"""
import argparse
import csv
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mp_reference as ref  # noqa: E402  (the scene reader and parameter container only)


class Field:
    """f(x) of model.md (3.10) for a batch of states (rows), real or complex."""

    def __init__(self, p):
        self.w = float(p.omega)
        self.M = float(p.Mr) + sum(b.m for b in p.balls)
        self.k, self.c, self.U = float(p.k), float(p.c), float(p.U)
        self.ml = [b.m * b.l for b in p.balls]
        self.l = [b.l for b in p.balls]
        self.j = [1.4 if b.rolling else 1.0 for b in p.balls]
        self.law = p.law
        self.d = [b.d for b in p.balls]
        self.mu = [b.mu for b in p.balls]
        self.kappa = p.kappa
        if self.law not in ("viscous", "none", "coulomb"):
            raise ref.InputError(f"the cycle reference handles the laws none, viscous and coulomb, not {self.law}")

    def friction(self, i, bd):
        if self.law == "none":
            return 0 * bd
        if self.law == "viscous":
            return -self.d[i] * self.l[i] * bd
        N = self.ml[i] * self.w ** 2
        return -self.mu[i] * N * (2 / math.pi) * np.arctan(self.kappa * bd)

    def __call__(self, x):
        w, M = self.w, self.M
        q1, q2, b1, b2, q1d, q2d, b1d, b2d = (x[:, i] for i in range(8))
        n = x.shape[0]
        A = np.zeros((n, 4, 4), dtype=x.dtype)
        A[:, 0, 0] = A[:, 1, 1] = M
        P1 = 2 * w * q2d + w * w * q1
        P2 = -2 * w * q1d + w * w * q2
        r0 = M * P1 - self.c * (q1d - w * q2) - self.k * q1 + w * w * self.U
        r1 = M * P2 - self.c * (q2d + w * q1) - self.k * q2
        rb = []
        for i, (be, bd) in enumerate(((b1, b1d), (b2, b2d))):
            ml = self.ml[i]
            sb, cb = np.sin(be), np.cos(be)
            A[:, 0, 2 + i] = A[:, 2 + i, 0] = -ml * sb
            A[:, 1, 2 + i] = A[:, 2 + i, 1] = ml * cb
            A[:, 2 + i, 2 + i] = self.j[i] * ml * self.l[i]
            r0 = r0 + ml * (bd + w) ** 2 * cb
            r1 = r1 + ml * (bd + w) ** 2 * sb
            rb.append(self.l[i] * self.friction(i, bd) + ml * (-P1 * sb + P2 * cb))
        b = np.stack([r0, r1, rb[0], rb[1]], axis=1)
        sdd = np.linalg.solve(A, b[:, :, None])[:, :, 0]
        return np.concatenate([x[:, 4:], sdd], axis=1)


def flow(f, x0, T, steps, h_cs=1e-30, record=False):
    """RK4 over [0, T] of x0 and of x0 + i h e_k (k = 0..7): (x(T), Phi, |q| samples)."""
    X = np.tile(np.asarray(x0, dtype=complex), (9, 1))
    for k in range(8):
        X[1 + k, k] += 1j * h_cs
    h = T / steps
    qs = []
    for _ in range(steps):
        if record:
            qs.append(math.hypot(X[0, 0].real, X[0, 1].real))
        k1 = f(X)
        k2 = f(X + 0.5 * h * k1)
        k3 = f(X + 0.5 * h * k2)
        k4 = f(X + h * k3)
        X = X + (h / 6) * (k1 + 2 * k2 + 2 * k3 + k4)
    xT = X[0].real.copy()
    Phi = np.stack([X[1 + k].imag / h_cs for k in range(8)], axis=1)
    return xT, Phi, qs


def cyclic_peak(v):
    n = len(v)
    k = int(np.argmax(v))
    a, b, c = v[(k - 1) % n], v[k], v[(k + 1) % n]
    den = a - 2 * b + c
    if den == 0:
        return b
    s = 0.5 * (a - c) / den
    return b - 0.25 * (a - c) * s


def orbit(f, guess, T0, steps):
    """Single shooting: Newton on (x0, T); the phase condition through `guess`."""
    g = np.asarray(guess, dtype=float)
    fg = f(g[None, :].astype(complex))[0].real
    fg = fg / np.linalg.norm(fg)
    x, T = g.copy(), float(T0)
    L = (f.U + sum(f.ml)) / f.M
    wH = 2 * math.pi / T0
    scale = np.array([L, L, 1, 1, L * wH, L * wH, wH, wH])
    last = math.inf
    for it in range(12):
        xT, Phi, _ = flow(f, x, T, steps)
        r = np.concatenate([xT - x, [(x - g) @ fg]])
        fT = f(xT[None, :].astype(complex))[0].real
        Jm = np.zeros((9, 9))
        Jm[:8, :8] = Phi - np.eye(8)
        Jm[:8, 8] = fT
        Jm[8, :8] = fg
        dz = np.linalg.solve(Jm, -r)
        x += dz[:8]
        T += dz[8]
        size = max(np.max(np.abs(dz[:8]) / scale), abs(dz[8]) / T)
        if size < 1e-13 or (it >= 2 and size > last / 2 and size < 1e-10):
            break  # converged, or at the rounding level
        last = size
    else:
        raise RuntimeError("the reference Newton did not converge")
    xT, Phi, qs = flow(f, x, T, steps, record=True)
    mult = np.linalg.eigvals(Phi)
    order = sorted(range(8), key=lambda i: (-abs(mult[i]), -mult[i].imag))
    return T, cyclic_peak(qs), [mult[i] for i in order], x


def load_orbit(scene, cycles_csv, index):
    """Row `index` of a cycles_P.csv, its parameter's name and the scene's field at that
    parameter. Raises ref.InputError, OSError, StopIteration or IndexError on bad input."""
    with open(cycles_csv) as fh:
        rows = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    if not rows:
        raise ref.InputError(f"{cycles_csv}: no orbit rows")
    row = rows[index]
    param = next(k for k in row if k not in ("cycle", "point"))
    return row, param, Field(ref.load_scene(scene, overrides=[f"{param}={row[param]}"]))


def orbit_start(row):
    """The orbit's x(0) from its CSV row, in the state order of model.md (3.10)."""
    return [float(row[c]) for c in ("q1_0", "q2_0", "beta1_0", "beta2_0", "dq1_0", "dq2_0", "dbeta1_0", "dbeta2_0")]


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("cycles_csv")
    ap.add_argument("--row", type=int, default=-1)
    ap.add_argument("--rtol", type=float, default=1e-6)
    ap.add_argument("--steps", type=int, default=3000)
    a = ap.parse_args(argv)
    try:
        row, param, f = load_orbit(a.scene, a.cycles_csv, a.row)
    except (ref.InputError, OSError, StopIteration, IndexError) as e:
        print(f"cycle_reference: {e}", file=sys.stderr)
        return 2
    guess = orbit_start(row)
    T_cpp, A_cpp = float(row["period"]), float(row["amplitude"])
    mu_cpp = [complex(float(row[f"mult_re{k}"]), float(row[f"mult_im{k}"])) for k in range(1, 9)]
    # RK4 at N, 2N, 4N steps; Richardson extrapolation removes the h^4 and h^5 terms of
    # the global error (E1 from N, 2N; E2 from 2N, 4N; R from E1, E2). |R - E2| bounds
    # E2's error, which is larger than R's: the self-check.
    try:
        runs = []
        x0 = guess
        for k in range(3):
            T, A, m, x0 = orbit(f, x0, T_cpp, a.steps * 2 ** k)
            runs.append(np.array([T, A] + list(m)))
    except (RuntimeError, np.linalg.LinAlgError) as e:
        print(f"cycle_reference: {e}", file=sys.stderr)
        return 2
    E1 = (16 * runs[1] - runs[0]) / 15
    E2 = (16 * runs[2] - runs[1]) / 15
    R = (32 * E2 - E1) / 31
    T2, A2, m2 = R[0].real, R[1].real, list(R[2:])
    self_err = float(np.max(np.abs(R - E2) / np.abs(R)))
    print(f"{param} = {row[param]}: RK4 at {a.steps} .. {4 * a.steps} steps, extrapolated; self-check {self_err:.2e}")
    if self_err > 1e-8:
        print("cycle_reference: the reference did not converge in the step count (use --steps)", file=sys.stderr)
        return 2
    worst = 0.0
    checks = [("period", T_cpp, T2), ("amplitude", A_cpp, A2)] + [(f"mult{k + 1}", mu_cpp[k], m2[k]) for k in range(8)]
    for name, got, want in checks:
        rel = abs(got - want) / abs(want)
        worst = max(worst, rel)
        print(f"  {name:10s} analyzer {got:.15g}  reference {want:.15g}  relative {rel:.2e}")
    if worst > a.rtol:
        print(f"cycle_reference: FAILED: worst relative difference {worst:.2e} > {a.rtol:g}", file=sys.stderr)
        return 1
    print(f"ok: worst relative difference {worst:.2e} <= {a.rtol:g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
