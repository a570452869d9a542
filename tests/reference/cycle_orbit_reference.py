#!/usr/bin/python3
"""Independent reference for periodic orbits of any period, stable or strongly unstable
(docs/model.md §17; the cost-against-error tables of docs/developers.md): the orbit through a
given profile, its period (or parameter) and all 8 Floquet multipliers.

    cycle_orbit_reference.py SCENE ORBITS.json [--intervals K] [--tol 1e-12] [--out OUT.json]

ORBITS.json: a list of orbits, each {"param": NAME, "value": p, "period": T, "fix": "param" or
"period", "profile": [[s, q1, q2, beta1, beta2, q1', q2', beta1', beta2'], ...]} (SI,
s = t/T in [0, 1), ascending: any points of the orbit, the start guess) and optionally
"multipliers": [[re, im], ...] (the analyzer's, compared here). With "fix": "param" the orbit
is the one at the given parameter value (its period is compared); with "period" the one of the
given period (its parameter is compared): near a homoclinic end the period at a fixed parameter
is ill-conditioned (dT/dp ~ 1/|p - p_hom|), the parameter at a fixed period is not.

Method (nothing of the C++ code): multiple shooting over K intervals of equal time, Newton on
(y_1 .. y_K, T, p) with the phase condition (y_1 - g) . f(g) = 0 (g the guess at s = 0) and the
fixed quantity; every flow is scipy's DOP853 on 10 complex trajectories at once (the state and
complex steps along the 8 state directions and the parameter), so the transition matrices are
the exact derivatives of the discrete flow. The field of model.md (3.7)-(3.10) is
cycle_reference.Field (written in numpy, also independent of the C++ code). Tolerance rtol =
tol, atol = tol times the scale of each component (model.md §17.2). The multipliers are the
eigenvalues of the product of the K transition matrices formed and solved in mpmath at 60
digits (the small multipliers of a strongly unstable orbit are lost in a double product). Each
orbit is computed at tol and at 10 tol: the self-check is the largest relative change of the
period, the parameter and the multipliers with |mu| > 1e-12 (the smaller ones: their modulus).
Exit 0, or 2 on bad input or a Newton that did not converge.
"""
import argparse
import json
import math
import os
import sys

import mpmath as mp
import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mp_reference as ref  # noqa: E402  (the scene reader)
from cycle_reference import Field  # noqa: E402  (the field in numpy)

H_CS = 1e-20  # complex step


class Flow:
    """The flow of one interval with the transition matrix and the parameter sensitivity, in
    the scaled variables of model.md §17.2: y = D^-1 x, Phi~ = D^-1 Phi D, z~ = D^-1 dx/dp, all
    80 components under DOP853's error control (the transition matrices resolve the fast
    rotor modes, which the state alone does not excite)."""

    def __init__(self, field, param, value, scale, tol):
        if param != "omega":
            raise ref.InputError("the reference varies omega only")
        self.f, self.scale, self.tol = field, scale, tol
        self.set_value(value)

    def set_value(self, value):
        # per row: 8 complex steps along the state directions, then one along the parameter
        w = np.full(9, complex(value))
        w[8] += 1j * H_CS
        self.w = w
        self.value = value

    def rhs(self, _t, v):
        D = self.scale
        y = v[:8]
        x = y * D
        X = np.tile(x.astype(complex), (9, 1))
        for k in range(8):
            X[k, k] += 1j * H_CS * D[k]
        kept = self.f.w
        self.f.w = self.w
        F = self.f(X)
        self.f.w = kept
        fx = F[0].real / D
        Jt = (F[:8].imag / H_CS).T / D[:, None]  # D^-1 J D: column k is d f / d y_k
        fp = F[8].imag / H_CS / D
        Phi = v[8:72].reshape(8, 8)
        z = v[72:80]
        return np.concatenate([fx, (Jt @ Phi).reshape(-1), Jt @ z + fp])

    def run(self, x0, h):
        """x0 (SI) over [0, h]: x(h) (SI), Phi (SI, 8x8), dx/dp (SI), steps."""
        D = self.scale
        v0 = np.concatenate([np.asarray(x0, dtype=float) / D, np.eye(8).reshape(-1), np.zeros(8)])
        r = solve_ivp(self.rhs, (0.0, h), v0, method="DOP853", rtol=self.tol, atol=self.tol)
        if not r.success:
            raise RuntimeError(f"DOP853 failed: {r.message}")
        v = r.y[:, -1]
        Phi = v[8:72].reshape(8, 8) * D[:, None] / D[None, :]
        return v[:8] * D, Phi, v[72:80] * D, r.t.size - 1


def field_at(field, x, p):
    """f(x) at the parameter value p (the flow's per-row parameter kept)."""
    kept = field.w
    field.w = complex(p)
    f = field(np.asarray(x, dtype=complex)[None, :])[0].real
    field.w = kept
    return f


def guess_points(profile, K):
    """The profile interpolated (periodic, linear in s) at s = j / K."""
    P = np.asarray(profile, dtype=float)
    s, X = P[:, 0], P[:, 1:]
    s_ext = np.concatenate([s, [s[0] + 1.0]])
    X_ext = np.vstack([X, X[:1]])
    pts = [np.array([np.interp(j / K, s_ext, X_ext[:, i]) for i in range(8)]) for j in range(K)]
    return pts


def solve(flow, field, orbit, K, fix, x_start=None, T_start=None, p_start=None):
    """Newton for one orbit; returns (p, T, x_points, Phis, steps per pass)."""
    scale = flow.scale
    xs = x_start if x_start is not None else guess_points(orbit["profile"], K)
    T = float(T_start if T_start is not None else orbit["period"])
    p = float(p_start if p_start is not None else orbit["value"])
    g = xs[0].copy()
    fg = field_at(field, g, p) / scale
    fg /= np.linalg.norm(fg)
    n = 8 * K + 2
    last = math.inf
    for it in range(30):
        flow.set_value(p)
        h = T / K
        J = np.zeros((n, n))
        r = np.zeros(n)
        Phis, steps = [], 0
        for j in range(K):
            xe, Phi, dp, st = flow.run(xs[j], h)
            steps += st
            nxt = (j + 1) % K
            rows = slice(8 * j, 8 * j + 8)
            r[rows] = (xe - xs[nxt]) / scale
            J[rows, 8 * j:8 * j + 8] = Phi * scale[None, :] / scale[:, None]
            J[rows, 8 * nxt:8 * nxt + 8] -= np.eye(8)
            fe = field_at(field, xe, p)
            J[rows, 8 * K] = fe / K / scale
            J[rows, 8 * K + 1] = dp / scale
            Phis.append(Phi)
        r[8 * K] = ((xs[0] - g) / scale) @ fg
        J[8 * K, 0:8] = fg
        if fix == "param":
            J[8 * K + 1, 8 * K + 1] = 1.0  # r = 0: p stays
        else:
            J[8 * K + 1, 8 * K] = 1.0
        d = np.linalg.solve(J, -r)
        for j in range(K):
            xs[j] = xs[j] + d[8 * j:8 * j + 8] * scale
        T += d[8 * K]
        p += d[8 * K + 1]
        size = max(np.max(np.abs(d[:8 * K])), abs(d[8 * K]) / T, abs(d[8 * K + 1]) / abs(p))
        if size < 1e-14 or (it >= 3 and size > 0.3 * last and size < 1e3 * flow.tol):
            return p, T, xs, Phis, steps
        last = size
    raise RuntimeError(f"the reference Newton did not converge (last step {size:.2e})")


def multipliers(Phis):
    """Eigenvalues of Phi_K ... Phi_1 at 60 digits, by modulus descending."""
    mp.mp.dps = 60
    P = mp.eye(8)
    for Phi in Phis:
        P = mp.matrix(Phi.tolist()) * P
    ev = mp.eig(P, left=False, right=False)
    return sorted(ev, key=order)


def order(z):
    """By modulus descending (rounded to 8 digits, so that a conjugate pair's rounding does
    not split it), then the positive imaginary part first."""
    m = abs(z)
    return (-round(float(mp.log(m)), 8) if m > 0 else math.inf, -float(mp.im(z)))


def rel(a, b):
    return abs(a - b) / abs(b)


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("orbits")
    ap.add_argument("--intervals", type=int, default=40)
    ap.add_argument("--tol", type=float, default=1e-12)
    ap.add_argument("--out")
    a = ap.parse_args(argv)
    try:
        with open(a.orbits) as fh:
            orbits = json.load(fh)
        results = []
        for orb in orbits:
            pname = orb["param"]
            field = Field(ref.load_scene(a.scene, overrides=[f"{pname}={orb['value']}"]))
            L = (field.U + sum(field.ml)) / field.M
            wH = 2 * math.pi / float(orb["period"])
            scale = np.array([L, L, 1, 1, L * wH, L * wH, wH, wH])
            fix = orb.get("fix", "param")
            runs = []
            x, T, p = None, None, None
            for tol in (10 * a.tol, a.tol):
                flow = Flow(field, pname, float(orb["value"]), scale, tol)
                p, T, x, Phis, steps = solve(flow, field, orb, a.intervals, fix, x, T, p)
                runs.append((p, T, multipliers(Phis), steps))
            (p1, T1, m1, _), (p2, T2, m2, steps) = runs
            changes = [rel(T1, T2), rel(p1, p2)]
            changes += [float(abs(u - v) / abs(v)) if abs(v) > 1e-12 else float(abs(abs(u) - abs(v))) for u, v in zip(m1, m2)]
            self_check = max(changes)
            out = {"param": pname, "value_given": orb["value"], "period_given": orb["period"], "fix": fix,
                   "value": p2, "period": T2, "multipliers": [[float(mp.re(z)), float(mp.im(z))] for z in m2],
                   "log_moduli": [float(mp.log(abs(z))) if z != 0 else -1e308 for z in m2],
                   "self_check": self_check, "self_check_each": changes, "steps_per_pass": steps, "intervals": a.intervals, "tol": a.tol}
            line = (f"{pname} {p2:.15g}  T {T2:.15g}  (fix {fix}; self-check {self_check:.1e} [T, p, mu: "
                    + " ".join(f"{c:.0e}" for c in changes) + f"], {steps} steps)")
            if fix == "param":
                out["period_error"] = rel(float(orb["period"]), T2)
                line += f"  period error {out['period_error']:.2e}"
            else:
                out["param_error"] = rel(float(orb["value"]), p2)
                line += f"  {pname} error {out['param_error']:.2e}"
            if "multipliers" in orb:
                given = sorted((complex(re, im) for re, im in orb["multipliers"]), key=order)
                errs = [float(abs(mp.mpc(g) - w) / abs(w)) if w != 0 else math.inf for g, w in zip(given, m2)]
                out["multiplier_errors"] = errs
                line += "  multipliers " + " ".join(f"{e:.1e}" for e in errs)
            print(line, flush=True)
            results.append(out)
    except (ref.InputError, OSError, KeyError, ValueError, json.JSONDecodeError) as e:
        print(f"cycle_orbit_reference: {e}", file=sys.stderr)
        return 2
    except (RuntimeError, np.linalg.LinAlgError) as e:
        print(f"cycle_orbit_reference: {e}", file=sys.stderr)
        return 2
    if a.out:
        with open(a.out, "w") as fh:
            json.dump(results, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
