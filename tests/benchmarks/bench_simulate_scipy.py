#!/usr/bin/python3
"""scipy.integrate.solve_ivp (Radau, BDF, LSODA, DOP853) on the problems of bench_simulate
(model.md §15), against the same reference end states, and the speed-against-error table.

    bench_simulate_scipy.py RESULTS.json [--repeat R] [--timeout S]

RESULTS.json is written by `bench_simulate SCENE --json RESULTS.json` in the same run. The
model (two balls, coulomb friction (4.4), run-up terms (9.1)-(9.4)) is written out here in
numpy; solve_ivp's implicit methods form their Jacobians by finite differences (its
default), LSODA by its own differences. Tolerances: rtol, atol = rtol * scale with the
scales of model.md §15.1 (L, L, 1 rad, 1 rad, L w, L w, w, w). Errors: the end state's
scaled max-norm distance to the reference. For each problem and target error (1e-4, 1e-5,
1e-6, 1e-9): the least wall time of a run that reached it, per method, and the ratio of
scipy's best to the analyzer's best, the analyzer with free steps (as scipy here) and with
its default 2000 samples by dense output (its error then the worst sample's, model.md
§15.1; scipy's runs record nothing, so that ratio is the conservative one).
"""
import argparse
import json
import math
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

M_R, K, C, U = 0.12, 7500.0, 2.0, 6.0e-7
M_B, L_B, R_B, J_B = 3.3e-5, 0.018, 1.0e-3, 1.4


def make_rhs(pr):
    mu, kappa = pr["mu"], pr["kappa"]
    w0, w1, alpha = pr["omega0"], pr["omega1"], pr["alpha"]
    M = M_R + 2 * M_B
    a = M_B * L_B
    t_ramp = (w1 - w0) / alpha if alpha > 0 else 0.0

    def rhs(t, x):
        if alpha > 0 and t < t_ramp:
            w, wd = w0 + alpha * t, alpha
        else:
            w, wd = w1, 0.0
        q1, q2, b1, b2, qd1, qd2, bd1, bd2 = x
        s = np.array([math.sin(b1), math.sin(b2)])
        c = np.array([math.cos(b1), math.cos(b2)])
        bd = np.array([bd1, bd2])
        P1 = 2 * w * qd2 + wd * q2 + w * w * q1
        P2 = -2 * w * qd1 - wd * q1 + w * w * q2
        F = -mu * M_B * L_B * w * w * (2 / math.pi) * np.arctan(kappa * bd)
        A = np.zeros((4, 4))
        A[0, 0] = A[1, 1] = M
        A[0, 2:] = -a * s
        A[1, 2:] = a * c
        A[2:, 0] = -M_B * s
        A[2:, 1] = M_B * c
        A[2, 2] = A[3, 3] = J_B * M_B * L_B
        cen = a * (bd + w) ** 2
        r = np.empty(4)
        r[0] = M * P1 - C * (qd1 - w * q2) - K * q1 + w * w * U + np.sum(cen * c + a * wd * s)
        r[1] = M * P2 - C * (qd2 + w * q1) - K * q2 - wd * U + np.sum(cen * s - a * wd * c)
        r[2:] = F + M_B * (-P1 * s + P2 * c) - M_B * wd * (L_B - (J_B - 1) * R_B)
        return np.concatenate((x[4:], np.linalg.solve(A, r)))

    return rhs


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("results")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=120.0, help="abandon a run after this long, and the tighter tolerances of its method [s]")
    a = ap.parse_args(argv)
    problems = json.load(open(a.results))
    targets = (1e-4, 1e-5, 1e-6, 1e-9)
    rows = []
    for pr in problems:
        L, w = pr["L"], pr["omega1"]
        scale = np.array([L, L, 1, 1, L * w, L * w, w, w])
        x0, xref = np.array(pr["x0"]), np.array(pr["x_ref"])
        rhs = make_rhs(pr)
        # sanity: the numpy model against the analyzer's at the start (same equations)
        best = {}
        for method in ("Radau", "BDF", "LSODA", "DOP853"):
            for rtol in (1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12):
                walls = []
                timed_out = False
                for _ in range(a.repeat):
                    t0 = time.perf_counter()
                    calls = [0]

                    def limited(t, x):  # a run longer than --timeout is abandoned (not reached)
                        calls[0] += 1
                        if calls[0] % 2000 == 0 and time.perf_counter() - t0 > a.timeout:
                            raise TimeoutError
                        return rhs(t, x)
                    try:
                        sol = solve_ivp(limited, (0.0, pr["t_end"]), x0, method=method, rtol=rtol, atol=rtol * scale)
                    except TimeoutError:
                        timed_out = True
                    walls.append(time.perf_counter() - t0)
                    if timed_out:
                        break
                wall = sorted(walls)[len(walls) // 2]
                if timed_out:
                    print(f"{pr['problem']:8} {method:7} {rtol:7.0e} abandoned after {wall:.0f} s (--timeout)", flush=True)
                    break
                err = float(np.max(np.abs(sol.y[:, -1] - xref) / scale)) if sol.status == 0 else float("inf")
                print(f"{pr['problem']:8} {method:7} {rtol:7.0e} {wall:11.3e} {sol.nfev:9d} {err:10.2e}"
                      + ("" if sol.status == 0 else f"  [{sol.message}]"), flush=True)
                for tgt in targets:
                    if err <= tgt:
                        best[(method, tgt)] = min(best.get((method, tgt), math.inf), wall)
                if wall > a.timeout:
                    print(f"{pr['problem']:8} {method:7} stopped: {wall:.0f} s > --timeout", flush=True)
                    break
        ours, ours_recorded = {}, {}
        for run in pr["runs"]:
            for tgt in targets:
                if run["ok"] and run["error"] <= tgt:
                    key = (run["method"], tgt)
                    ours[key] = min(ours.get(key, math.inf), run["wall"])
                if run["ok"] and run.get("error_recorded", math.inf) <= tgt:
                    key = (run["method"], tgt)
                    ours_recorded[key] = min(ours_recorded.get(key, math.inf), run["wall_recorded"])
        rows.append((pr["problem"], best, ours, ours_recorded))
    print("\n| problem | target error | analyzer, free steps (method) | analyzer, 2000 samples (method) | Radau | BDF "
          "| LSODA | DOP853 | scipy's best / analyzer free | scipy's best / analyzer with samples |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    fmt = lambda v: "-" if not math.isfinite(v) else (f"{v * 1e3:.3g} ms" if v < 1 else f"{v:.3g} s")
    ratio = lambda a, b: f"{a / b:.0f}x" if math.isfinite(a) and math.isfinite(b) else "-"
    for name, best, ours, ours_recorded in rows:
        for tgt in targets:
            mine = min(((v, m) for (m, t), v in ours.items() if t == tgt), default=(math.inf, "-"))
            rec = min(((v, m) for (m, t), v in ours_recorded.items() if t == tgt), default=(math.inf, "-"))
            cols = [best.get((m, tgt), math.inf) for m in ("Radau", "BDF", "LSODA", "DOP853")]
            sbest = min(cols)
            print(f"| {name} | {tgt:g} | {fmt(mine[0])} ({mine[1]}) | {fmt(rec[0])} ({rec[1]}) | "
                  + " | ".join(fmt(c) for c in cols) + f" | {ratio(sbest, mine[0])} | {ratio(sbest, rec[0])} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
