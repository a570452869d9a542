#!/usr/bin/python3
"""Independent reference for ONE periodic orbit of a non-balanced state with STIFF coulomb
balls on an anisotropic support (docs/model.md §10.14, §10.18): its initial point x(0) and
all 8 Floquet multipliers, against `stability-scan equilibria SCENE --format json`.

Why a second reference: forced_orbit_reference.py integrates the 72-dimensional variational
system with scipy's Radau; with ball rates of 1e7-1e8 1/s one flow did not finish in 15
minutes. Here the analyzer's route (Radau IIA collocation with fixed steps, exact derivatives
of the discrete map, stiff multipliers from the frozen fast eigenvalues) is replaced by:
  * the field of forced_orbit_reference.Field (written from the fixed-frame support force,
    equilibria from the closed forms (5.7), (5.9)); Jacobians by the complex step;
  * the orbit: single shooting, the 8-dimensional INCREMENT w(t) = y(t) - y(0) integrated by
    scipy's adaptive Radau (rtol 1e-12, atol 1e-20: a stuck ball's angle is nearly neutral,
    so its increment, not the angle, must carry the relative accuracy), Newton on
    w(pi/omega; y0) = 0 at delta = 1 from the equilibrium of the mean system (the orbit is
    within O(|kappa|/k_bar) of it);
  * the monodromy: fourth-order Magnus (two Gauss points, exact exponentials by scipy's
    expm, so the stiff ball rates decay as they must) of Phi' = J(x(t), t) Phi along the
    dense output, 2048 steps (128 for the Newton matrix Phi - I);
  * multipliers: numpy eigenvalues of that monodromy.
Self-check: the orbit again at rtol 1e-10 and the monodromy with 1024 steps must agree to
1e-9 relative (else exit 2).

Usage: forced_orbit_stiff_reference.py SCENE.toml --json CPP.json [--orbit K] [--rtol 1e-8]
K (1-based) in the order of the mean system's equilibria (together, then opposite).
Exit 0: the analyzer's orbit closest to the reference's x(0) agrees within rtol on x(0)
(relative to each coordinate's scale) and on every multiplier with |rho| >= 1e-6 (smaller:
absolute 1e-9), and every orbit of the analyzer is converged; 1: a mismatch; 2: bad input
or a reference that did not converge.
"""
import argparse
import json
import math
import os
import sys

import numpy as np
from scipy.integrate import solve_ivp
from scipy.linalg import expm

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from forced_orbit_reference import Field  # noqa: E402  (the field and the closed-form equilibria)


class StiffOrbit:
    def __init__(self, f, x_eq):
        self.f = f
        self.T = math.pi / f.w
        L = math.hypot(x_eq[0], x_eq[1])
        self.D = np.array([L, L, 1, 1, L * f.w, L * f.w, f.w, f.w])

    def jac(self, t, x):
        """df/dx at (t, x) [SI] by the complex step."""
        h = 1e-30 * self.D
        X = np.tile(x.astype(complex), (8, 1))
        X[np.arange(8), np.arange(8)] += 1j * h
        return (self.f(t, X).imag / h[:, None]).T

    def increment(self, y0, rtol):
        """w(T) = y(T) - y0 (scaled) and the dense solution x(t) [SI]."""
        D = self.D

        def rhs(t, w):
            return self.f(t, ((y0 + w) * D)[None, :])[0] / D

        def jac(t, w):
            return self.jac(t, (y0 + w) * D) * D[None, :] / D[:, None]

        # absolute tolerances: 1e-2 rtol on the rotor's O(1) scaled increments; 1e-20 on the
        # balls' (their increments are ~1e-12, and an error a in them moves the orbit by a / 1e-9)
        atol = np.array([1e-2, 1e-2, 1e-8, 1e-8, 1e-2, 1e-2, 1e-8, 1e-8]) * rtol
        r = solve_ivp(rhs, (0, self.T), np.zeros(8), method="Radau", jac=jac, rtol=rtol, atol=atol,
                      dense_output=True)
        if not r.success:
            raise RuntimeError(r.message)
        return r.y[:, -1], (lambda t: (y0 + r.sol(t)) * D)

    def monodromy(self, x_of_t, steps):
        """Magnus-4: Omega = h/2 (A1 + A2) + sqrt(3)/12 h^2 [A2, A1], Phi <- expm(Omega) Phi."""
        h = self.T / steps
        c1, c2 = 0.5 - math.sqrt(3) / 6, 0.5 + math.sqrt(3) / 6
        Phi = np.eye(8)
        for k in range(steps):
            t1, t2 = (k + c1) * h, (k + c2) * h
            A1, A2 = self.jac(t1, x_of_t(t1)), self.jac(t2, x_of_t(t2))
            Om = 0.5 * h * (A1 + A2) + math.sqrt(3) / 12 * h * h * (A2 @ A1 - A1 @ A2)
            Phi = expm(Om) @ Phi
        return Phi

    def solve(self, y, rtol, steps):
        """Newton at delta = 1 from y (scaled): the orbit is within O(|kappa|/k_bar) of the
        equilibrium, inside Newton's basin; the monodromy of the last iterate's flow (whose
        Newton step was below 1e-12) gives the multipliers."""
        D = self.D
        self.f.delta = 1.0
        for it in range(12):
            w, x_of_t = self.increment(y, rtol)
            Phi = np.diag(1 / D) @ self.monodromy(x_of_t, 128) @ np.diag(D)
            dy = np.linalg.solve(Phi - np.eye(8), -w)
            y = y + dy
            print(f"    Newton {it + 1}: step {np.max(np.abs(dy)):.2e}, closure {np.max(np.abs(w)):.2e}", flush=True)
            if np.max(np.abs(dy)) < 1e-12:
                break
        else:
            raise RuntimeError(f"Newton did not converge (last step {np.max(np.abs(dy)):.2e})")
        Phi = self.monodromy(x_of_t, steps)
        ev = np.linalg.eigvals(Phi)
        order = sorted(range(8), key=lambda i: (-abs(ev[i]), -ev[i].imag))
        return y * D, [ev[i] for i in order], float(np.max(np.abs(w)))


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("--json", required=True)
    ap.add_argument("--orbit", type=int, default=1)
    ap.add_argument("--rtol", type=float, default=1e-8)
    a = ap.parse_args(argv)
    try:
        f = Field(a.scene)
        with open(a.json) as fh:
            cpp = json.load(fh)["periodic_orbits"]
    except (OSError, KeyError, ValueError) as e:
        print(f"forced_orbit_stiff_reference: {e}", file=sys.stderr)
        return 2
    eqs = f.equilibria()
    print(f"{a.scene}: {len(eqs)} aligned equilibria of the mean system; the analyzer reports {len(cpp)} orbit(s), "
          f"{sum(o['status'] == 'converged' for o in cpp)} converged")
    if len(cpp) != len(eqs) or any(o["status"] != "converged" for o in cpp):
        print("forced_orbit_stiff_reference: FAILED: the analyzer did not find every orbit", file=sys.stderr)
        return 1
    name, x_eq = eqs[a.orbit - 1]
    s = StiffOrbit(f, x_eq)
    try:
        x0, mult, closure = s.solve(x_eq / s.D, 1e-12, 2048)
        x0b, multb, _ = s.solve(x0 / s.D, 1e-10, 1024)
    except (RuntimeError, np.linalg.LinAlgError) as e:
        print(f"forced_orbit_stiff_reference: {name}: {e}", file=sys.stderr)
        return 2
    D = s.D
    self_err = max(float(np.max(np.abs(x0 - x0b) / D)),
                   max(abs(m1 - m2) / max(abs(m1), 1e-6) for m1, m2 in zip(mult, multb)))
    k = min(range(len(cpp)), key=lambda i: float(np.max(np.abs(np.array(cpp[i]["state0"]) - x0) / D)))
    o = cpp[k]
    print(f"  {name} {a.orbit} (analyzer: {o['kind']}); reference closure {closure:.1e}, self-check {self_err:.2e}")
    if self_err > 1e-9:
        print("forced_orbit_stiff_reference: the reference is not converged", file=sys.stderr)
        return 2
    worst = 0.0
    checks = [(f"x0[{i}]", o["state0"][i], x0[i], D[i]) for i in range(8)]
    got = [complex(*m) for m in o["floquet_multipliers"]]
    checks += [(f"rho{i + 1}", got[i], mult[i], 0.0) for i in range(8)]
    for cname, g, want, floor in checks:
        if cname.startswith("rho") and abs(want) < 1e-6:
            rel = abs(g - want) / 1e-9 * a.rtol
        else:
            rel = abs(g - want) / max(abs(want), floor)
        worst = max(worst, rel)
        print(f"    {cname:8s} analyzer {g:.15g}  reference {want:.15g}  relative {rel:.2e}")
    if worst > a.rtol:
        print(f"forced_orbit_stiff_reference: FAILED: worst relative difference {worst:.2e} > {a.rtol:g}",
              file=sys.stderr)
        return 1
    print(f"within {a.rtol:g} (worst {worst:.2e})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
