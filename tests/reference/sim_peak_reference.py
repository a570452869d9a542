#!/usr/bin/python3
"""Independent reference for the largest |q| of a run-up through resonance and for the
samples of `simulate` between the integrator's steps (docs/model.md §9, §15.1, §15.4).

The run: data/scenes/viscous.toml (two balls in a damping fluid, non-stiff), omega from
100 to 400 rad/s at 1000 rad/s^2 (through omega_n = 249.93 rad/s at t = 0.15 s), held to
t = 0.6 s; balls at rest at 2 and 4 rad. The equations (9.1)-(9.4) with viscous friction
(4.3) are written out here in numpy (not taken from the C++ model) and integrated by
scipy's solve_ivp DOP853 at rtol 1e-12 (atol = rtol x the scales of model.md §15.1) with
dense output, in two pieces that meet at the ramp's end (where omega' jumps). The largest
|q| is located by a root-find (brentq) on d|q|^2/dt / 2 = q . q' of the dense solution,
bracketed on a fine grid; the reference's own error is estimated by a second integration
at rtol 1e-13 and must be below 1e-10 relative.

Checks `stability-scan simulate` at its default tolerance:
  * max_q_abs within 1e-8 relative of the reference's maximum (the peak located between
    samples, model.md §15.4); t_max_q_abs within the interval on which the reference's |q|
    stays within 1e-8 of its maximum (the run-up's peak is flat: |q''| / |q| ~ 800 1/s^2,
    so that interval is +-5e-6 s); max_q_abs_run_up the same value (the peak lies in the
    ramp);
  * every sample of simulation.csv (interpolated between steps, model.md §15.1) within
    10 rtol of the reference in the scaled norm of §15.1 (q / L, rad, q' / (L w), beta' / w):
    the global error model.md §15.1 states for the calibrated tolerance (the interpolant adds
    at most rtol); rtol the default 1e-7 unless --rtol is given;
  * the sampled maximum of the CSV's q_abs column is below the located one (it is a
    sample of the same curve).

usage: sim_peak_reference.py BINARY SOURCE_DIR [--rtol T]
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

# data/scenes/viscous.toml: rotor, two equal rolling balls (j = 7/5), viscous d.
M_R, K, C, U = 0.12, 7500.0, 2.0, 6.0e-7
M_B, L_B, R_B, J_B, D_B = 3.3e-5, 0.018, 1.0e-3, 1.4, 2.0e-3
W0, W1, ALPHA, T_END = 100.0, 400.0, 1000.0, 0.6
RTOL_DEFAULT = 1e-7  # simulate's default tolerance (SimulationOptions::rtol, docs/cli.md)
BETA0 = (2.0, 4.0)
T_RAMP = (W1 - W0) / ALPHA
M = M_R + 2 * M_B
L = (U + 2 * M_B * L_B) / M
SCALE = np.array([L, L, 1.0, 1.0, L * W1, L * W1, W1, W1])


def rhs_factory(ramping):
    """The field of (9.1)-(9.4) on one segment of the profile (omega' constant on it)."""
    a = M_B * L_B

    def rhs(t, x):
        w, wd = (W0 + ALPHA * t, ALPHA) if ramping else (W1, 0.0)
        q1, q2, b1, b2, qd1, qd2, bd1, bd2 = x
        b = np.array([b1, b2])
        bd = np.array([bd1, bd2])
        s, c = np.sin(b), np.cos(b)
        # (9.1): a1 = q1'' - P1, a2 = q2'' - P2
        P1 = 2 * w * qd2 + wd * q2 + w * w * q1
        P2 = -2 * w * qd1 - wd * q1 + w * w * q2
        A = np.zeros((4, 4))
        r = np.empty(4)
        # (9.2), (9.3): the unknowns' terms on the left
        A[0, 0] = M
        A[0, 2:] = -a * s
        r[0] = M * P1 - C * (qd1 - w * q2) - K * q1 + w * w * U + np.sum(a * ((bd + w) ** 2 * c + wd * s))
        A[1, 1] = M
        A[1, 2:] = a * c
        r[1] = M * P2 - C * (qd2 + w * q1) - K * q2 - wd * U + np.sum(a * ((bd + w) ** 2 * s - wd * c))
        # (9.4) with F = -d l beta' (4.3)
        F = -D_B * L_B * bd
        A[2:, 0] = -M_B * s
        A[2:, 1] = M_B * c
        A[2, 2] = A[3, 3] = J_B * M_B * L_B
        r[2:] = F + M_B * (-P1 * s + P2 * c) - M_B * wd * (L_B - (J_B - 1) * R_B)
        return np.concatenate((x[4:], np.linalg.solve(A, r)))

    return rhs


def integrate(rtol):
    """Dense solutions of the two segments [0, T_RAMP] and [T_RAMP, T_END]."""
    x0 = np.array([0.0, 0.0, BETA0[0], BETA0[1], 0.0, 0.0, 0.0, 0.0])
    pieces = []
    for (ta, tb), ramping in (((0.0, T_RAMP), True), ((T_RAMP, T_END), False)):
        sol = solve_ivp(rhs_factory(ramping), (ta, tb), x0, method="DOP853", rtol=rtol, atol=rtol * SCALE,
                        dense_output=True)
        if sol.status != 0:
            raise RuntimeError(f"solve_ivp: {sol.message}")
        pieces.append((ta, tb, sol.sol))
        x0 = sol.y[:, -1]
    return pieces


def state_at(pieces, t):
    for ta, tb, sol in pieces:
        if ta <= t <= tb:
            return sol(t)
    raise ValueError(t)


def curvature(pieces, t, dt=1e-4):
    """d2|q|/dt2 at t by a central difference on the dense output (its error O(dt^2))."""
    q = [math.hypot(*state_at(pieces, t + k * dt)[:2]) for k in (-1, 0, 1)]
    return (q[0] - 2 * q[1] + q[2]) / dt ** 2


def peak(pieces):
    """The largest |q| over [0, T_END]: the ends of each piece and every interior maximum,
    a root of g = q . q' where g changes sign from + to - (brentq on the dense output)."""
    best = (0.0, 0.0)
    for ta, tb, sol in pieces:
        for t in (ta, tb):
            x = sol(t)
            best = max(best, (math.hypot(x[0], x[1]), t))
        grid = np.linspace(ta, tb, 60001)
        X = sol(grid)
        g = X[0] * X[4] + X[1] * X[5]
        for k in np.nonzero((g[:-1] > 0) & (g[1:] <= 0))[0]:
            tk = brentq(lambda t: float(sol(t)[0] * sol(t)[4] + sol(t)[1] * sol(t)[5]), grid[k], grid[k + 1],
                        xtol=1e-16, rtol=4 * np.finfo(float).eps, maxiter=200)
            x = sol(tk)
            best = max(best, (math.hypot(x[0], x[1]), tk))
    return best


def main():
    binary, source = sys.argv[1], sys.argv[2]
    rtol_args = sys.argv[3:5] if len(sys.argv) >= 5 and sys.argv[3] == "--rtol" else []
    ref = integrate(1e-12)
    q_max, t_max = peak(ref)
    q_check, t_check = peak(integrate(1e-13))
    ref_err = abs(q_check - q_max) / q_max
    t_window = math.sqrt(2e-8 * q_max / abs(curvature(ref, t_max)))  # |q| >= (1 - 1e-8) q_max within it
    print(f"reference: largest |q| {q_max:.15e} m at t = {t_max:.12f} s (DOP853 rtol 1e-12; against rtol 1e-13: "
          f"{ref_err:.1e} relative, {abs(t_check - t_max):.1e} s); within 1e-8 of it for {t_window:.1e} s either side")
    ok = ref_err < 1e-10
    if not ok:
        print("FAIL the reference's own error estimate exceeds 1e-10")
    with tempfile.TemporaryDirectory() as tmp:
        js = os.path.join(tmp, "summary.json")
        cmd = [binary, "simulate", os.path.join(source, "data/scenes/viscous.toml"), "--ramp", f"{W0:g}:{W1:g}:{ALPHA:g}",
               "--t-end", str(T_END), "--balls", ",".join(str(b) for b in BETA0), "--no-chart", "--quiet", "-o", tmp,
               "--summary", js] + rtol_args
        res = subprocess.run(cmd, capture_output=True, text=True)
        if res.returncode != 0:
            print(f"FAIL simulate: exit {res.returncode}: {res.stderr}")
            return 1
        with open(js) as fh:
            s = json.load(fh)
        with open(os.path.join(tmp, "simulation.csv")) as fh:
            rows = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    q_err = abs(s["max_q_abs"] - q_max) / q_max
    t_err = abs(s["t_max_q_abs"] - t_max)
    run_up = s["max_q_abs_run_up"]
    run_up_err = abs(run_up - q_max) / q_max if run_up is not None else math.inf
    good = q_err <= 1e-8 and t_err <= t_window and run_up_err <= 1e-8
    print(f"{'ok  ' if good else 'FAIL'} max_q_abs {s['max_q_abs']:.15e} m: {q_err:.1e} relative, "
          f"t_max_q_abs {s['t_max_q_abs']:.12f} s: {t_err:.1e} s, max_q_abs_run_up {run_up_err:.1e} relative "
          f"(method {s['method']}, {s['stats']['steps']} steps)")
    ok = ok and good
    names = ["q1", "q2", "beta1", "beta2", "dq1", "dq2", "dbeta1", "dbeta2"]
    worst, at = 0.0, 0.0
    sampled = 0.0
    for row in rows:
        t = float(row["t"])
        x = np.array([float(row[n]) for n in names])
        e = float(np.max(np.abs(x - state_at(ref, t)) / SCALE))
        if e > worst:
            worst, at = e, t
        sampled = max(sampled, float(row["q_abs"]))
    rtol = float(rtol_args[1]) if rtol_args else RTOL_DEFAULT
    good = worst <= 10 * rtol and len(rows) == 2001
    print(f"{'ok  ' if good else 'FAIL'} {len(rows)} samples: largest scaled distance to the reference {worst:.2e} "
          f"at t = {at:g} s")
    ok = ok and good
    good = sampled <= s["max_q_abs"] * (1 + 1e-14)
    print(f"{'ok  ' if good else 'FAIL'} the largest sample of q_abs {sampled:.15e} m is "
          f"{(q_max - sampled) / q_max:.1e} (relative) below the reference's maximum, and below max_q_abs")
    ok = ok and good
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
