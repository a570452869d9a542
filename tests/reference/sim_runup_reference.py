#!/usr/bin/python3
"""Independent reference for one run-up (docs/model.md §9): the equations (9.1)-(9.4)
written out again here (not from the C++ model: the second derivatives are solved from
the three equations as printed, by Gaussian elimination), integrated by classical RK4
at two fixed steps with Richardson extrapolation, in plain Python floats (no numpy).

The run: the default rotor with two viscous balls (non-stiff, so that a fixed-step
method is exact enough), omega from 150 to 350 rad/s at 2000 rad/s^2 (through
omega_n = 249.93 rad/s at t = 0.05 s), held to t = 0.15 s; balls at rest at 2 and 4 rad.

Checks `stability-scan simulate` (rtol 1e-11, bsimp, rk8pd and bdf) against it: every component
of the end state in the scaled norm of model.md §15.1 (q / L, angles in rad, q' / (L w),
beta' / w) within 1e-7 (the reference's own Richardson error estimate is printed and
must be below 1e-8), and the largest |q| of the run (located between the samples, model.md
§15.4) within 1e-8 relative of the reference's: the quintic through |q| and d|q|/dt =
q . q' / |q| at the largest point of the reference's 1e-5 s grid and its two neighbours,
maximized (its error O(h^6), ~1e-14 here); the time of the maximum within the interval on
which the reference's |q| stays within 1e-8 of its maximum.

usage: sim_runup_reference.py BINARY SOURCE_DIR
"""
import json
import math
import os
import subprocess
import sys
import tempfile

M_R, K, C, U = 0.12, 7500.0, 2.0, 6.0e-7
BALLS = [dict(m=3.3e-5, l=0.018, r=1.0e-3, j=1.4, d=1.0e-4) for _ in range(2)]
W0, W1, ALPHA, T_END = 150.0, 350.0, 2000.0, 0.15
BETA0 = [2.0, 4.0]


T_RAMP = (W1 - W0) / ALPHA


def speed(t, ramping):
    """omega and omega' on the segment a step belongs to (omega' jumps at T_RAMP, a step
    boundary: deciding by the stage time would put one stage of the last ramp step on the
    held segment, a first-order error)."""
    return (W0 + ALPHA * t, ALPHA) if ramping else (W1, 0.0)


def solve(A, b):
    n = len(b)
    A = [row[:] + [b[i]] for i, row in enumerate(A)]
    for c in range(n):
        piv = max(range(c, n), key=lambda r: abs(A[r][c]))
        A[c], A[piv] = A[piv], A[c]
        for r in range(c + 1, n):
            f = A[r][c] / A[c][c]
            for k in range(c, n + 1):
                A[r][k] -= f * A[c][k]
    x = [0.0] * n
    for r in reversed(range(n)):
        x[r] = (A[r][n] - sum(A[r][k] * x[k] for k in range(r + 1, n))) / A[r][r]
    return x


def rhs(t, x, ramping):
    n = len(BALLS)
    w, wd = speed(t, ramping)
    q1, q2 = x[0], x[1]
    be = x[2:2 + n]
    qd1, qd2 = x[n + 2], x[n + 3]
    bd = x[n + 4:]
    M = M_R + sum(b["m"] for b in BALLS)
    # (9.1): a1 = q1'' - P1, a2 = q2'' - P2
    P1 = 2 * w * qd2 + wd * q2 + w * w * q1
    P2 = -2 * w * qd1 - wd * q1 + w * w * q2
    A = [[0.0] * (n + 2) for _ in range(n + 2)]
    b = [0.0] * (n + 2)
    # (9.2): M (q1'' - P1) + c (q1' - w q2) + k q1 = w^2 U + sum a_i [(bd + w)^2 cos + (b'' + wd) sin]
    A[0][0] = M
    b[0] = M * P1 - C * (qd1 - w * q2) - K * q1 + w * w * U
    # (9.3): M (q2'' - P2) + c (q2' + w q1) + k q2 = -wd U + sum a_i [(bd + w)^2 sin - (b'' + wd) cos]
    A[1][1] = M
    b[1] = M * P2 - C * (qd2 + w * q1) - K * q2 - wd * U
    for i, ball in enumerate(BALLS):
        a = ball["m"] * ball["l"]
        s, co = math.sin(be[i]), math.cos(be[i])
        A[0][2 + i] = -a * s
        b[0] += a * ((bd[i] + w) ** 2 * co + wd * s)
        A[1][2 + i] = a * co
        b[1] += a * ((bd[i] + w) ** 2 * s - wd * co)
        # (9.4): j m l b'' = F + m (a1 sin - a2 cos) - m wd (l - (j - 1) r), F = -d l bd (4.3)
        F = -ball["d"] * ball["l"] * bd[i]
        A[2 + i][2 + i] = ball["j"] * ball["m"] * ball["l"]
        A[2 + i][0] = -ball["m"] * s
        A[2 + i][1] = ball["m"] * co
        b[2 + i] = F + ball["m"] * (-P1 * s + P2 * co) - ball["m"] * wd * (ball["l"] - (ball["j"] - 1) * ball["r"])
    acc = solve(A, b)
    return x[n + 2:] + acc


EVERY = 0.001  # the program's sample interval
GRID = 1e-5    # the reference's |q| is kept on this grid (a whole number of steps)


def rk4(h):
    """The end state, and |q| and d|q|/dt = q . q' / |q| at every grid time k * GRID."""
    n = len(BALLS)
    x = [0.0, 0.0] + BETA0 + [0.0] * (n + 2)
    steps = int(round(T_END / h))
    per_point = int(round(GRID / h))
    q_abs, q_rate = [], []

    def keep():
        r = math.hypot(x[0], x[1])
        q_abs.append(r)
        q_rate.append((x[0] * x[n + 2] + x[1] * x[n + 3]) / r if r > 0 else 0.0)

    keep()
    t = 0.0
    ramp_steps = int(round(T_RAMP / h))
    for k in range(steps):
        if k > 0 and k % per_point == 0:
            keep()
        t = k * h
        ramping = k < ramp_steps
        k1 = rhs(t, x, ramping)
        k2 = rhs(t + h / 2, [xi + h / 2 * ki for xi, ki in zip(x, k1)], ramping)
        k3 = rhs(t + h / 2, [xi + h / 2 * ki for xi, ki in zip(x, k2)], ramping)
        k4 = rhs(t + h, [xi + h * ki for xi, ki in zip(x, k3)], ramping)
        x = [xi + h / 6 * (a + 2 * b + 2 * c + d) for xi, a, b, c, d in zip(x, k1, k2, k3, k4)]
    keep()
    return x, q_abs, q_rate


def quintic_peak(v, r, k):
    """The maximum of the quintic through values v and rates r at grid points k - 1, k, k + 1
    (s = (t - t_k) / GRID): its value, time and curvature d2|q|/dt2 there."""
    A, b = [], []
    for j, s in enumerate((-1.0, 0.0, 1.0)):
        A.append([s ** i for i in range(6)])
        b.append(v[k - 1 + j])
        A.append([i * s ** (i - 1) if i else 0.0 for i in range(6)])
        b.append(r[k - 1 + j] * GRID)
    c = solve(A, b)
    s = 0.0
    for _ in range(50):  # Newton on p'(s) = 0
        d1 = sum(i * c[i] * s ** (i - 1) for i in range(1, 6))
        d2 = sum(i * (i - 1) * c[i] * s ** (i - 2) for i in range(2, 6))
        step = d1 / d2
        s -= step
        if abs(step) < 1e-15:
            break
    d2 = sum(i * (i - 1) * c[i] * s ** (i - 2) for i in range(2, 6))
    return sum(c[i] * s ** i for i in range(6)), (k + s) * GRID, d2 / GRID ** 2


def scales():
    n = len(BALLS)
    M = M_R + sum(b["m"] for b in BALLS)
    L = (U + sum(b["m"] * b["l"] for b in BALLS)) / M
    return [L, L] + [1.0] * n + [L * W1, L * W1] + [W1] * n


def main():
    binary, source = sys.argv[1], sys.argv[2]
    # The ramp's end (t = 0.1 s) is a breakpoint of the fixed steps (0.1 / h is an integer).
    h = 5e-6
    (coarse, q_coarse, r_coarse), (fine, q_fine, r_fine) = rk4(2 * h), rk4(h)
    ref = [f + (f - c) / 15 for f, c in zip(fine, coarse)]  # Richardson, RK4 order 4
    q_ref = [f + (f - c) / 15 for f, c in zip(q_fine, q_coarse)]
    r_ref = [f + (f - c) / 15 for f, c in zip(r_fine, r_coarse)]
    k_max = max(range(1, len(q_ref) - 1), key=lambda k: q_ref[k])
    q_max, t_q_max, curvature = quintic_peak(q_ref, r_ref, k_max)
    q_est = abs(quintic_peak(q_fine, r_fine, k_max)[0] - q_max) / q_max
    # |q| stays within 1e-8 of its maximum for |t - t_max| <= sqrt(2e-8 q_max / |q''|).
    t_window = math.sqrt(2e-8 * q_max / abs(curvature))
    print(f"reference: largest |q| {q_max:.12e} m at t = {t_q_max:.9f} s (Richardson error estimate "
          f"{q_est:.1e} relative; within 1e-8 of it for {t_window:.1e} s either side)")
    sc = scales()
    est = max(abs(f - c) / 15 / s for f, c, s in zip(fine, coarse, sc))
    print(f"reference: RK4 h = {h:g} s and {2 * h:g} s, Richardson error estimate {est:.2e} (scaled)")
    ok = est < 1e-8
    with open(os.path.join(source, "data/scenes/default.toml")) as fh:
        text = fh.read()
    text = text.replace('law = "coulomb"', 'law = "viscous"').replace("mu = 0.002", "d = 1.0e-4")
    text = "\n".join(line for line in text.splitlines() if not line.startswith("kappa"))
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "viscous.toml")
        with open(scene, "w") as fh:
            fh.write(text)
        for method in ("bsimp", "rk8pd", "bdf"):
            js = os.path.join(tmp, f"{method}.json")
            cmd = [binary, "simulate", scene, "--ramp", f"{W0}:{W1}:{ALPHA}", "--t-end", str(T_END), "--balls",
                   ",".join(str(b) for b in BETA0), "--rtol", "1e-11", "--method", method, "--every", "0.001",
                   "--no-chart", "--quiet", "-o", os.path.join(tmp, method), "--summary", js]
            res = subprocess.run(cmd, capture_output=True, text=True)
            if res.returncode != 0:
                print(f"FAIL {method}: exit {res.returncode}: {res.stderr}")
                ok = False
                continue
            with open(js) as fh:
                s = json.load(fh)
            err = max(abs(a - b) / c for a, b, c in zip(s["state_end"], ref, sc))
            # The largest |q| of the run, located between the samples (model.md §15.4).
            q_err = abs(s["max_q_abs"] - q_max) / q_max
            good = err < 1e-7 and abs(s["t_end"] - T_END) < 1e-15 and q_err < 1e-8
            good = good and abs(s["t_max_q_abs"] - t_q_max) <= t_window
            print(f"{'ok  ' if good else 'FAIL'} {method}: scaled error of the end state {err:.2e}, "
                  f"largest |q| {q_err:.1e} relative at t = {s['t_max_q_abs']:.9f} s "
                  f"({s['stats']['steps']} steps, passes omega_n at {s['t_omega_n']})")
            ok = ok and good
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
