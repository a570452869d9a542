#!/usr/bin/python3
"""Independent check of the Campbell view `stability-scan sweep --param omega` writes for an
anisotropic support (campbell_omega.csv, docs/model.md §10.15), at one speed of the sweep.

How it differs from the C++ route (Hill's method: the harmonics x_k of each Floquet mode are an
eigenvector of the truncated Hill matrix, the ladder member chosen by centroid):
  * J(t) from mp_floquet.py (the fixed-frame support force differentiated at each t, ball rows
    and mass matrix of the 80-digit isotropic reference mp_reference.py), its three harmonics
    read off as floquet_crossing_reference.py does;
  * the fundamental matrix Phi(t) over one period pi/omega by scipy's DOP853 (rtol 1e-12), with
    dense output; the Floquet pairs (rho, v) are numpy.linalg.eig of the monodromy Phi(pi/omega);
  * the harmonics of a mode are the FFT of the periodic part p(t) = e^{-lambda t} Phi(t) v,
    lambda = (omega/pi) Log rho (principal branch), over 64 samples of one period;
  * the fixed-frame lines +-(Im lambda + omega + 2 k omega) of each body (rotor M_r, ball i at
    q + i l_i e^{i beta_i} dbeta_i, mass m_i), paired and weighted as model.md (10.15.2)-(10.15.3)
    says, written again here from the text; then Omega, zeta, rotor share (16.3.1) and forward share.

Usage: floquet_campbell_reference.py SCENE.toml CAMPBELL.csv STEP [--rtol 1e-7]
STEP: the sweep's value index (column `step`). Every mode of every balanced state at that
speed must match a CSV row (re_fixed and whirl_frequency to rtol * omega, zeta to rtol, the
shares to 1e-6) and the counts must agree; exits 1 otherwise. Two balls, [[ball]] tables.
"""
import argparse
import cmath
import csv
import math
import os
import sys

import numpy as np
from mpmath import mp, mpf
from scipy.integrate import solve_ivp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import floquet_crossing_reference as fcr  # noqa: E402
import mp_floquet as mf  # noqa: E402
import mp_reference as ref  # noqa: E402

SAMPLES = 64


def modes_at(p, K, C, omega):
    p.omega = float(omega)
    w = p.omega
    T = math.pi / w
    out = []
    for e in ref._balanced(p):
        with mp.workdps(40):
            e = ref.newton_polish(p, e) or e
        beta = [float(e.b1), float(e.b2)]
        J0, Jc, Js = fcr.harmonics(p, K, C, [mpf(0), mpf(0), mpf(e.b1), mpf(e.b2)])
        n = J0.shape[0]

        def rhs(t, y):
            return ((J0 + np.cos(2 * w * t) * Jc + np.sin(2 * w * t) * Js) @ y.reshape(n, n)).ravel()

        sol = solve_ivp(rhs, (0.0, T), np.eye(n).ravel(), method="DOP853", rtol=1e-12, atol=1e-14,
                        dense_output=True)
        rho, V = np.linalg.eig(sol.y[:, -1].reshape(n, n))
        ts = np.arange(SAMPLES) * T / SAMPLES
        Phis = [sol.sol(t).reshape(n, n) for t in ts]
        masses = [float(p.Mr)] + [float(b.m) for b in p.balls]
        radii = [float(b.l) for b in p.balls]
        M = float(p.M())
        modes = []
        for j in range(n):
            if rho[j].imag < -1e-12 * abs(rho[j]):
                continue  # the conjugate partner represents the pair
            lam = cmath.log(rho[j]) * w / math.pi
            if abs(rho[j].imag) <= 1e-12 * abs(rho[j]):
                lam = complex(lam.real, 0.0 if rho[j].real > 0 else w)
            P = np.array([np.exp(-lam * t) * (Phi @ V[:, j]) for t, Phi in zip(ts, Phis)])  # periodic part
            X = np.fft.fft(P, axis=0) / SAMPLES  # column k: coefficient of e^{2 i omega k t}
            ks = np.fft.fftfreq(SAMPLES, 1.0 / SAMPLES).astype(int)
            plus, minus = {}, {}  # pair k: w+ of harmonic k, w- of harmonic k + 1
            rotor_e = ball_e = 0.0
            common = 0.0
            wsum = sum(b.j() * b.m * b.l ** 2 for b in p.balls)
            for idx, k in enumerate(ks):
                v = X[idx]
                bodies = [(masses[0], v[0], v[1])]
                for i in range(2):
                    bodies.append((masses[1 + i], v[0] - radii[i] * math.sin(beta[i]) * v[2 + i],
                                   v[1] + radii[i] * math.cos(beta[i]) * v[2 + i]))
                for m, x, y in bodies:
                    plus[k] = plus.get(k, 0.0) + m * abs((x + 1j * y) / 2) ** 2
                    minus[k - 1] = minus.get(k - 1, 0.0) + m * abs((np.conj(x) + 1j * np.conj(y)) / 2) ** 2
                rotor_e += M * (abs(v[0]) ** 2 + abs(v[1]) ** 2)
                ball_e += sum(float(b.j()) * b.m * b.l ** 2 * abs(v[2 + i]) ** 2 for i, b in enumerate(p.balls))
                common += abs(sum(float(b.j()) * b.m * b.l ** 2 * v[2 + i] for i, b in enumerate(p.balls))) ** 2
            keys = sorted(set(plus) | set(minus))
            total = sum(plus.get(k, 0) + minus.get(k, 0) for k in keys)
            best = max(keys, key=lambda k: (plus.get(k, 0) + minus.get(k, 0), plus.get(k, 0)))
            f = lam.imag + w + 2 * w * best
            pos, neg = (plus.get(best, 0), minus.get(best, 0)) if f >= 0 else (minus.get(best, 0), plus.get(best, 0))
            Omega = abs(f) if pos >= neg else -abs(f)
            forward = sum((plus.get(k, 0) if lam.imag + w + 2 * w * k >= 0 else minus.get(k, 0)) for k in keys)
            modes.append({"re": lam.real, "whirl": Omega, "zeta": -lam.real / abs(complex(lam.real, Omega)),
                          "rotor_share": rotor_e / (rotor_e + ball_e), "forward_share": forward / total,
                          "balls_together": common / (float(wsum) * ball_e) if ball_e > 0 else 0.0})
        out.append(modes)
    return out


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("campbell")
    ap.add_argument("step", type=int)
    ap.add_argument("--rtol", type=float, default=1e-7)
    a = ap.parse_args(argv)
    mp.dps = 30
    p, K, C = mf.load(a.scene)
    with open(a.campbell) as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#")) if int(r["step"]) == a.step]
    if not rows:
        raise SystemExit(f"FAIL: no row with step {a.step} in {a.campbell}")
    omega = float(rows[0]["omega"])
    states = modes_at(p, K, C, omega)
    failures = 0
    ref_count = sum(len(s) for s in states)
    print(f"omega = {omega} rad/s: {len(states)} balanced states, {ref_count} modes (reference), {len(rows)} rows")
    if ref_count != len(rows):
        print(f"FAIL: {ref_count} reference modes against {len(rows)} CSV rows")
        failures += 1
    worst = 0.0
    for s, modes in enumerate(states):
        for m in modes:
            def dist(r):
                return abs(complex(float(r["re_fixed"]) - m["re"], float(r["whirl_frequency"]) - m["whirl"]))
            def share_diff(r):
                return max(abs(float(r["rotor_share"]) - m["rotor_share"]),
                           abs(float(r["forward_share"]) - m["forward_share"]),
                           abs(float(r["balls_together"]) - m["balls_together"]))
            # The mirror balanced states have the same eigenvalues and mirrored shares: among the
            # rows at this eigenvalue (rtol), the one whose shares match.
            d0 = min(dist(r) for r in rows)
            same = [r for r in rows if dist(r) <= max(d0, a.rtol * omega)]
            r = min(same, key=share_diff)
            d = dist(r) / omega
            share = share_diff(r)
            zeta = abs(float(r["zeta"]) - m["zeta"])
            worst = max(worst, d)
            ok = d <= a.rtol and zeta <= a.rtol and share <= 1e-6
            print(f"{'ok  ' if ok else 'FAIL'} state {s + 1}: Omega {m['whirl']:+.10f} (csv {float(r['whirl_frequency']):+.10f}, "
                  f"{r['label']}), re {m['re']:.8f}, |d|/omega {d:.2e}, zeta diff {zeta:.1e}, shares diff {share:.1e}")
            failures += not ok
    print(f"largest |fixed-frame eigenvalue difference| / omega: {worst:.2e}")
    if failures:
        raise SystemExit(1)


if __name__ == "__main__":
    main()
