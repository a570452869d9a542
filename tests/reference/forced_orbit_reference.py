#!/usr/bin/python3
"""Independent reference for the non-balanced states on an anisotropic support
(docs/model.md §10.14): the pi/omega-periodic orbits that continue the aligned equilibria
of the mean system, with all 8 Floquet multipliers, to compare with
`stability-scan equilibria SCENE --format json` (its "periodic_orbits" array).

How it differs from the C++ route (multiple shooting with GSL, continuation in delta by
the arclength engine, multipliers by periodic orthogonal iteration, analytic Jacobian):
  * the field of model.md (3.7)-(3.10) is written here again, for two balls, with the
    support force taken from the fixed frame, F = -R^T K_f R q - R^T C_f R (q' + omega J2 q),
    R = R(omega t) (no decomposition into mean and oscillating parts);
  * the equilibria of the mean system from the closed forms (5.7), (5.9);
  * SINGLE shooting: Newton on x0 with phi(pi/omega; x0) - x0 = 0, at delta = 1/4, 1/2,
    3/4, 1 of the homotopy K_f(delta) = k_bar I + delta (K_f - k_bar I) (natural steps);
  * the flow and its variational equation by scipy's DOP853 (viscous) or Radau (stiff
    coulomb), the Jacobian by the complex step (exact to rounding), in scaled coordinates;
  * multipliers: eigenvalues of the monodromy (numpy); max |q| and mean |q| from 256
    uniform samples by the FFT (the mean exactly, the max by maximizing the trigonometric
    interpolant with scipy's bounded Brent search).
The run is repeated at a 100x looser integration tolerance; the two must agree to 1e-9
relative (else exit 2: the reference itself is not converged).

Usage: forced_orbit_reference.py SCENE.toml --json CPP.json [--rtol 1e-8] [--orbit K ...]
Exit 0: every orbit found by both, each within rtol (multipliers with |rho| >= 1e-6
relative, smaller ones absolute 1e-9; q_abs_max, q_abs_mean, x(0)); 1: a mismatch;
2: bad input or a reference that did not converge.
"""
import argparse
import json
import math
import sys
import tomllib

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar


class Field:
    """f(x, t; delta) of two balls on an anisotropic support, for a batch of states (rows)."""

    def __init__(self, path):
        with open(path, "rb") as fh:
            t = tomllib.load(fh)
        r, fr = t["rotor"], t["friction"]
        self.w = float(t["speed"]["omega"])
        self.Mr = float(r["mass"])
        self.U = float(r["unbalance"])
        self.Kf = np.array([[r["stiffness_x"], r.get("stiffness_xy", 0.0)], [r.get("stiffness_xy", 0.0), r["stiffness_y"]]], float)
        self.Cf = np.array([[r["damping_x"], r.get("damping_xy", 0.0)], [r.get("damping_xy", 0.0), r["damping_y"]]], float)
        self.kbar, self.cbar = np.trace(self.Kf) / 2, np.trace(self.Cf) / 2
        balls = t["ball"]
        if len(balls) != 2:
            raise ValueError("the reference handles two balls")
        rolling = t.get("rolling", True)
        self.m = [float(b["mass"]) for b in balls]
        self.l = [float(b["race_radius"]) for b in balls]
        self.j = [1.4 if b.get("rolling", rolling) else 1.0 for b in balls]
        self.ml = [m * l for m, l in zip(self.m, self.l)]
        self.M = self.Mr + sum(self.m)
        self.law = fr["law"]
        if self.law == "viscous":
            self.d = [float(b.get("d", fr.get("d"))) for b in balls]
        elif self.law == "coulomb":
            self.mu = [float(b.get("mu", fr.get("mu"))) for b in balls]
            self.kappa = float(fr["kappa"])
        else:
            raise ValueError(f"the reference handles viscous and coulomb, not {self.law}")
        self.delta = 1.0

    def support(self, t):
        """K_rot, C_rot at delta: R^T K_f(delta) R."""
        c, s = math.cos(self.w * t), math.sin(self.w * t)
        R = np.array([[c, -s], [s, c]])
        I = np.eye(2)
        K = self.kbar * I + self.delta * (self.Kf - self.kbar * I)
        C = self.cbar * I + self.delta * (self.Cf - self.cbar * I)
        return R.T @ K @ R, R.T @ C @ R

    def friction(self, i, bd):
        if self.law == "viscous":
            return -self.d[i] * self.l[i] * bd
        N = self.ml[i] * self.w ** 2
        return -self.mu[i] * N * (2 / math.pi) * np.arctan(self.kappa * bd)

    def __call__(self, t, x):
        w, M = self.w, self.M
        q1, q2, b1, b2, q1d, q2d, b1d, b2d = (x[:, i] for i in range(8))
        n = x.shape[0]
        Kr, Cr = self.support(t)
        v1, v2 = q1d - w * q2, q2d + w * q1  # q' + omega J2 q: the inertial velocity on the rotating axes
        A = np.zeros((n, 4, 4), dtype=x.dtype)
        A[:, 0, 0] = A[:, 1, 1] = M
        P1 = 2 * w * q2d + w * w * q1
        P2 = -2 * w * q1d + w * w * q2
        r0 = M * P1 - (Kr[0, 0] * q1 + Kr[0, 1] * q2) - (Cr[0, 0] * v1 + Cr[0, 1] * v2) + w * w * self.U
        r1 = M * P2 - (Kr[1, 0] * q1 + Kr[1, 1] * q2) - (Cr[1, 0] * v1 + Cr[1, 1] * v2)
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

    def equilibria(self):
        """The aligned equilibria of the mean system: (5.7) together, (5.9) opposite."""
        w = self.w
        K, C = self.kbar - w * w * self.M, self.cbar * w
        out = []
        for name, S, sign in (("together", self.ml[0] + self.ml[1], 1), ("opposite", self.ml[0] - self.ml[1], -1)):
            # K U sin b + C U cos b + C S = 0  ->  R sin(b + phi) = -C S
            R, phi = self.U * math.hypot(K, C), math.atan2(C, K)
            if abs(C * S) > R:
                continue
            a = math.asin(-C * S / R)
            for b in (a - phi, math.pi - a - phi):
                q = w * w * (self.U + S * complex(math.cos(b), math.sin(b))) / complex(K, C)
                b2 = b if sign > 0 else b + math.pi
                out.append((name, np.array([q.real, q.imag, b % (2 * math.pi), b2 % (2 * math.pi), 0, 0, 0, 0])))
        return out


class Shooter:
    def __init__(self, f, x_eq, tol):
        self.f, self.tol = f, tol
        self.T = math.pi / f.w
        L = math.hypot(x_eq[0], x_eq[1])
        self.D = np.array([L, L, 1, 1, L * f.w, L * f.w, f.w, f.w])
        J = self.jac(0.0, x_eq)
        self.stiff = np.max(np.abs(np.linalg.eigvals(J))) / f.w > 1e3

    def jac(self, t, x):
        h = 1e-30 * self.D
        X = np.tile(x.astype(complex), (8, 1))
        X[np.arange(8), np.arange(8)] += 1j * h
        return (self.f(t, X).imag / h[:, None]).T  # column k: df/dx_k

    def rhs(self, t, z):
        y = z[:8]
        x = y * self.D
        fx = self.f(t, x[None, :].astype(float))[0]
        Js = self.jac(t, x) * self.D[None, :] / self.D[:, None]  # D^-1 J D
        Phi = z[8:].reshape(8, 8)
        return np.concatenate([fx / self.D, (Js @ Phi).ravel()])

    def rhs_jac(self, t, z):
        Js = self.jac(t, z[:8] * self.D) * self.D[None, :] / self.D[:, None]
        return np.kron(np.eye(9), Js)

    def flow(self, y0, samples=None):
        """The increment w(t) = y(t) - y0 and the transition matrix over the period.

        The increment, not the state, is integrated (with an absolute tolerance 1e-8 of the
        state's): a stuck coulomb ball's angle is nearly neutral (multiplier 1 - 1e-9), so an
        absolute error of tol on the angle itself would move the fixed point by tol / 1e-9."""
        z0 = np.concatenate([np.zeros(8), np.eye(8).ravel()])
        atol = np.concatenate([np.full(8, self.tol * 1e-8), np.full(64, self.tol)])
        kw = dict(method="Radau", jac=self.rhs_jac) if self.stiff else dict(method="DOP853")
        # the samples and the end point (the monodromy is the last column)
        te = None if samples is None else np.linspace(0, self.T, samples + 1)
        r = solve_ivp(lambda t, z: self.rhs(t, np.concatenate([y0 + z[:8], z[8:]])), (0, self.T), z0,
                      rtol=self.tol, atol=atol, t_eval=te,
                      **(dict(kw, jac=lambda t, z: self.rhs_jac(t, np.concatenate([y0 + z[:8], z[8:]])))
                         if self.stiff else kw))
        if not r.success:
            raise RuntimeError(r.message)
        r.y[:8] += y0[:, None]
        return r.y[:8, -1] - y0, r.y[8:, -1].reshape(8, 8), r

    def newton(self, y):
        for _ in range(15):
            w, Phi, _ = self.flow(y)  # w = y(T) - y(0), integrated as such
            dy = np.linalg.solve(Phi - np.eye(8), -w)
            y = y + dy
            if np.max(np.abs(dy)) < 50 * self.tol:
                return y
        raise RuntimeError("the reference Newton did not converge")


def orbit(f, x_eq, tol):
    s = Shooter(f, x_eq, tol)
    y = x_eq / s.D
    for delta in (0.25, 0.5, 0.75, 1.0):
        f.delta = delta
        y = s.newton(y)
    # samples: |q| at t = 0 .. T(1 - 1/N) (solve_ivp's dense output), and the monodromy at T
    N = 256
    yT, Phi, r = s.flow(y, samples=N)
    qs = np.hypot(r.y[0, :N] * s.D[0], r.y[1, :N] * s.D[1])
    c = np.fft.rfft(qs) / N

    def interp(th):
        k = np.arange(1, len(c) - 1)
        return c[0].real + 2 * np.sum((c[1:-1] * np.exp(1j * k * th)).real)

    k0 = int(np.argmax(qs))
    th0 = 2 * math.pi * k0 / N
    best = minimize_scalar(lambda th: -interp(th), bounds=(th0 - 4 * math.pi / N, th0 + 4 * math.pi / N),
                           method="bounded", options={"xatol": 1e-13})
    qmax = -best.fun
    ev = np.linalg.eigvals(Phi)
    order = sorted(range(8), key=lambda i: (-abs(ev[i]), -ev[i].imag))
    return dict(x0=y * s.D, qmax=qmax, qmean=c[0].real, mult=[ev[i] for i in order])


def compare(got, want, floor=0.0):
    """|got - want| relative to max(|want|, floor) (floor: the coordinate's natural size)."""
    scale = max(abs(want), floor)
    rel = abs(got - want) / scale if scale > 0 else abs(got - want)
    return rel


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("--json", required=True)
    ap.add_argument("--rtol", type=float, default=1e-8)
    ap.add_argument("--tol", type=float, default=1e-13, help="integration tolerance of the reference")
    ap.add_argument("--orbit", type=int, action="append",
                    help="check only this orbit (1-based, in the order of the mean system's equilibria: "
                         "together, then opposite); repeatable. All are still required to be reported.")
    a = ap.parse_args(argv)
    try:
        f = Field(a.scene)
        with open(a.json) as fh:
            cpp = json.load(fh)["periodic_orbits"]
    except (OSError, KeyError, ValueError) as e:
        print(f"forced_orbit_reference: {e}", file=sys.stderr)
        return 2
    eqs = f.equilibria()
    print(f"{a.scene}: {len(eqs)} aligned equilibria of the mean system; the analyzer reports {len(cpp)} orbit(s)")
    if len(cpp) != len(eqs):
        print("forced_orbit_reference: FAILED: the orbit count differs", file=sys.stderr)
        return 1
    if any(o["status"] != "converged" for o in cpp):
        print("forced_orbit_reference: FAILED: the analyzer did not find every orbit", file=sys.stderr)
        return 1
    worst = 0.0
    for index, (name, x_eq) in enumerate(eqs, start=1):
        if a.orbit and index not in a.orbit:
            continue
        try:
            ref = orbit(f, x_eq, a.tol)
            loose = orbit(f, x_eq, a.tol * 100)
        except (RuntimeError, np.linalg.LinAlgError) as e:
            print(f"forced_orbit_reference: {name}: {e}", file=sys.stderr)
            return 2
        L = math.hypot(ref["x0"][0], ref["x0"][1])
        D = np.array([L, L, 1, 1, L * f.w, L * f.w, f.w, f.w])
        self_err = max(abs(ref["qmax"] - loose["qmax"]) / ref["qmax"],
                       max(abs(m1 - m2) / max(abs(m1), 1e-6) for m1, m2 in zip(ref["mult"], loose["mult"])),
                       float(np.max(np.abs(ref["x0"] - loose["x0"]) / D)))
        # the analyzer's orbit: the nearest x(0)
        k = min(range(len(cpp)), key=lambda i: float(np.max(np.abs(np.array(cpp[i]["state0"]) - ref["x0"]) / D)))
        o = cpp[k]
        print(f"  {name} (analyzer: {o['kind']}, {o['status']}); reference self-check {self_err:.2e}")
        if self_err > 1e-9:
            print("forced_orbit_reference: the reference is not converged in its tolerance", file=sys.stderr)
            return 2
        checks = [("q_abs_max", o["q_abs_max"], ref["qmax"], 0.0), ("q_abs_mean", o["q_abs_mean"], ref["qmean"], 0.0)]
        checks += [(f"x0[{i}]", o["state0"][i], ref["x0"][i], D[i]) for i in range(8)]
        mult = [complex(*m) for m in o["floquet_multipliers"]]
        checks += [(f"rho{i + 1}", mult[i], ref["mult"][i], 0.0) for i in range(8)]
        for cname, got, want, floor in checks:
            if cname.startswith("rho") and abs(want) < 1e-6:
                rel = abs(got - want) / 1e-9 * a.rtol  # below 1e-6: absolute 1e-9 (scaled to rtol)
            else:
                rel = compare(got, want, floor)
            worst = max(worst, rel)
            print(f"    {cname:10s} analyzer {got:.15g}  reference {want:.15g}  relative {rel:.2e}")
        if o["status"] != "converged":
            worst = math.inf
    if worst > a.rtol:
        print(f"forced_orbit_reference: FAILED: worst relative difference {worst:.2e} > {a.rtol:g}", file=sys.stderr)
        return 1
    print(f"all orbits within {a.rtol:g} (worst {worst:.2e})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
