#!/usr/bin/python3
"""Independent reference for the stick-slip dynamics of `coulomb-set` friction
(docs/model.md §14.5-§14.8), two balls at constant speed, against
`stability-scan simulate SCENE --balls B1,B2 --summary FILE`.

The reference shares no code with the C++ integrator and uses other methods:
  * the equations of motion written out from (3.7)-(3.9) in numpy;
  * the stick phase as the saddle-point (KKT) system [[A, -E_S], [E_S^T, 0]] of the
    constraint beta_S'' = 0 with the stuck forces as multipliers (the C++ code eliminates
    them through A^-1 instead, (14.5.3));
  * scipy's DOP853 (rtol 1e-12) with its own dense-output event location (terminal
    events sigma_i beta_i' = 0 and mu_i N_i - |F_i| = 0).
Checked: the end angles to 1e-9 rad, the stuck flags at the end, and the end point in
the stick set (max |s_i| <= 1). The C++ run uses rtol 1e-11, where the convergence test
of tests/test_stick_slip.cpp puts its own end-angle error near 1e-13 rad; the two agree
to 2e-14 rad on tests/scenes/stickslip/runup.toml (17 switches in 1 s), so 1e-9 leaves
room for other machines' rounding while catching any wrong switch (a misplaced event moves
the end angles by 1e-3 rad or more).

usage: stick_slip_reference.py STABILITY_SCAN SCENE.toml B1,B2 T_END
"""
import json
import math
import os
import subprocess
import sys
import tempfile
import tomllib

import numpy as np
from scipy.integrate import solve_ivp


def load(path):
    with open(path, "rb") as f:
        t = tomllib.load(f)
    r = t["rotor"]
    balls = t["ball"]
    mu = t["friction"].get("mu")
    j = 1.4 if t.get("rolling", True) else 1.0
    return dict(Mr=r["mass"], k=r["stiffness"], c=r["damping"], U=r["unbalance"],
                m=np.array([b["mass"] for b in balls]), l=np.array([b["race_radius"] for b in balls]),
                mu=np.array([b.get("mu", mu) for b in balls]), j=j, w=t["speed"]["omega"])


class Model:
    def __init__(self, P):
        self.P = P
        self.n = len(P["m"])
        self.M = P["Mr"] + P["m"].sum()
        self.a = P["m"] * P["l"]
        self.N = P["m"] * P["l"] * P["w"] ** 2  # (1.6)

    def A_b(self, y):
        """A(beta) of (3.8) and b(s, s') of (3.9) without the friction term."""
        P, n, w, a = self.P, self.n, self.P["w"], self.a
        q1, q2 = y[0], y[1]
        be = y[2:2 + n]
        dq1, dq2 = y[2 + n], y[3 + n]
        dbe = y[4 + n:4 + 2 * n]
        A = np.zeros((n + 2, n + 2))
        A[0, 0] = A[1, 1] = self.M
        A[0, 2:] = A[2:, 0] = -a * np.sin(be)
        A[1, 2:] = A[2:, 1] = a * np.cos(be)
        A[2:, 2:] = np.diag(P["j"] * P["m"] * P["l"] ** 2)
        b = np.zeros(n + 2)
        b[0] = w * w * P["U"] + np.sum(a * (dbe + w) ** 2 * np.cos(be)) + self.M * (2 * w * dq2 + w * w * q1) \
            - P["c"] * (dq1 - w * q2) - P["k"] * q1
        b[1] = np.sum(a * (dbe + w) ** 2 * np.sin(be)) + self.M * (-2 * w * dq1 + w * w * q2) \
            - P["c"] * (dq2 + w * q1) - P["k"] * q2
        b[2:] = a * ((-2 * w * dq2 - w * w * q1) * np.sin(be) - (2 * w * dq1 - w * w * q2) * np.cos(be))
        return A, b

    def solve(self, y, stuck, sigma):
        """Accelerations and friction forces: slipping F = -sigma mu N, stuck from the KKT system."""
        n = self.n
        A, b = self.A_b(y)
        F = np.zeros(n)
        for i in range(n):
            if not stuck[i]:
                F[i] = -sigma[i] * self.P["mu"][i] * self.N[i]
        rhs = b.copy()
        rhs[2:] += self.P["l"] * F
        S = [i for i in range(n) if stuck[i]]
        k = len(S)
        K = np.zeros((n + 2 + k, n + 2 + k))
        K[:n + 2, :n + 2] = A
        for c, i in enumerate(S):
            K[2 + i, n + 2 + c] = -self.P["l"][i]  # the stuck force enters row 2 + i as l_i F_i
            K[n + 2 + c, 2 + i] = 1.0               # beta_i'' = 0
        sol = np.linalg.solve(K, np.concatenate([rhs, np.zeros(k)]))
        for c, i in enumerate(S):
            F[i] = sol[n + 2 + c]
        return sol[:n + 2], F


def run(P, beta0, t_end):
    mdl = Model(P)
    n = mdl.n
    y = np.zeros(2 * n + 4)
    y[2:2 + n] = beta0
    stuck = [False] * n
    sigma = [1.0] * n

    def settle(t, y, released=()):
        for i in range(n):
            if not stuck[i] and y[4 + n + i] == 0.0 and i not in released:
                stuck[i] = True
        while True:
            _, F = mdl.solve(y, stuck, sigma)
            worst, excess = -1, 0.0
            for i in range(n):
                if stuck[i]:
                    e = (abs(F[i]) - P["mu"][i] * mdl.N[i]) / (P["mu"][i] * mdl.N[i])
                    if e > excess:
                        worst, excess = i, e
            if worst < 0:
                return
            stuck[worst] = False
            sigma[worst] = -1.0 if F[worst] > 0 else 1.0

    def rhs(t, y):
        acc, _ = mdl.solve(y, stuck, sigma)
        d = np.concatenate([y[n + 2:], acc])
        for i in range(n):
            if stuck[i]:
                d[2 + i] = 0.0
                d[n + 4 + i] = 0.0
        return d

    def event(i):
        def g(t, y):
            if stuck[i]:
                _, F = mdl.solve(y, stuck, sigma)
                return (P["mu"][i] * mdl.N[i] - abs(F[i])) / (P["mu"][i] * mdl.N[i])
            return sigma[i] * y[4 + n + i] / P["w"]
        g.terminal = True
        g.direction = -1
        return g

    L = (P["U"] + mdl.a.sum()) / mdl.M
    atol = np.concatenate([[L * 1e-12] * 2, [1e-12] * n, [L * P["w"] * 1e-12] * 2, [P["w"] * 1e-12] * n])
    t = 0.0
    settle(t, y)
    events = 0
    while t < t_end:
        sol = solve_ivp(rhs, (t, t_end), y, method="DOP853", rtol=1e-12, atol=atol,
                        events=[event(i) for i in range(n)])
        t = sol.t[-1]
        y = sol.y[:, -1].copy()
        if sol.status == 1:
            events += 1
            released = []
            for i in range(n):
                if len(sol.t_events[i]) == 0:
                    continue
                if stuck[i]:  # at the limit (the located root may lie on either side): it slips
                    _, F = mdl.solve(y, stuck, sigma)
                    stuck[i] = False
                    sigma[i] = -1.0 if F[i] > 0 else 1.0
                    released.append(i)
                else:
                    y[4 + n + i] = 0.0
            settle(t, y, released)
            if events > 10000:
                raise RuntimeError("too many events")
        elif sol.status != 0:
            raise RuntimeError(sol.message)
    return y, stuck, mdl, events


def main():
    exe, scene, balls, t_end = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
    beta0 = np.array([float(x) for x in balls.split(",")])
    P = load(scene)
    y, stuck, mdl, events = run(P, beta0, t_end)
    n = mdl.n
    with tempfile.TemporaryDirectory() as d:
        summary = os.path.join(d, "s.json")
        subprocess.run([exe, "simulate", scene, "--balls", balls, "--t-end", str(t_end), "--rtol", "1e-11",
                        "--no-chart", "--quiet", "-o", d, "--summary", summary], check=True)
        with open(summary) as f:
            js = json.load(f)
    end = np.array(js["state_end"][2:2 + n])
    ss = js["stick_slip"]
    ok = True
    diff = np.max(np.abs(end - y[2:2 + n]))
    print(f"reference: {events} switches; end beta {y[2:2 + n]}, stuck {stuck}")
    print(f"program:   end beta {end}, stuck {ss['stuck']}, max|s| {ss['max_abs_s']}, in set {ss['in_stick_set']}")
    print(f"end angle difference {diff:.3e} rad (tolerance 1e-9)")
    if not diff <= 1e-9:
        ok = False
    if [bool(s) for s in ss["stuck"]] != stuck:
        print("stuck flags differ")
        ok = False
    # the end point in the stick set (14.2), from the reference's own q of (5.4)
    P_w = P["w"]
    W = P["U"] + np.sum(mdl.a * np.exp(1j * y[2:2 + n]))
    q = P_w ** 2 * W / complex(P["k"] - P_w ** 2 * mdl.M, P["c"] * P_w)
    s = (q.real * np.sin(y[2:2 + n]) - q.imag * np.cos(y[2:2 + n])) / (P["mu"] * P["l"])
    print(f"reference max|s| {np.max(np.abs(s)):.9f}")
    if all(stuck) and not np.max(np.abs(s)) <= 1:
        ok = False
    if all(stuck) != ss["in_stick_set"]:
        ok = False
    print("PASS" if ok else "FAIL")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
