#!/usr/bin/python3
"""Checks the C++ program's first Lyapunov coefficients against an independent mpmath one.

    check_lyapunov.py BINARY SCENE PARAM TO [--set NAME=VALUE ...] [--rtol 1e-8]
    check_lyapunov.py BINARY SCENE PARAM TO --param2 P2 --to2 V [--set ...]   (GH points)

With --param2 the program's two-parameter run (`continue ... --param2 P2 --to2 V`) is
checked instead: every generalized Hopf point (GH row of boundary_PARAM_P2.csv) against
the reference's own, the zero of l1 along the Hopf curve found by the secant method on
P2, the Hopf point relocated in PARAM at each trial P2 as above: both parameters to
--rtol.

Runs `BINARY continue SCENE --param PARAM --to TO --no-chart` (two balls) and, at every
converged HB row of its special_PARAM.csv, recomputes l1 (Kuznetsov's formula,
docs/model.md §6.3) with mp_special.first_lyapunov: the model written again in mpmath
(mp_reference.py), its second and third derivatives by central differences at 100
digits with two step sizes (1e-20 and 1e-17; their agreement is the reference's own
accuracy, asked here to be >= 12 digits), eigenvectors by inverse iteration at that
precision. The Hopf point itself is located again at 60 digits, independently of the
C++ program: the family member's closed-form state (mp_special.member_state, the member
nearest the printed state) at parameter v, the eigenvalue of its Jacobian nearest
i * (printed frequency), and the secant method on its real part from the printed v. (At
the printed point itself, rounded to double, l1 of a stiff scene moves by its condition
times 1e-16: 3e-9 relative at kappa = 1e6.) The C++ value must agree to --rtol (default
1e-8, the issue's target: the C++ forms are exact Taylor coefficients in long double). At least one HB row must be found (a
check of nothing fails). Exit 0 pass, 1 mismatch or nothing checked, 2 bad input.
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mp_reference as R  # noqa: E402
import mp_special as S  # noqa: E402
import verdict_cache  # noqa: E402
from mpmath import mp, mpc, mpf  # noqa: E402


def relocate(p0, par, family, value, printed_state, printed_w):
    """The Hopf point near the printed one, at 60 digits: (params, state, w_H)."""
    with mp.workdps(60):
        def dist(s):
            return max(abs(s[0] - printed_state[0]), abs(s[1] - printed_state[1]),
                       R._angdist(s[2], printed_state[2]), R._angdist(s[3], printed_state[3]))
        members = [m for m in (1, 2) if S.member_state(par.at(p0, value), family, m) is not None]
        if not members:
            raise RuntimeError(f"no {family} member exists at the printed parameter {value}")
        member = min(members, key=lambda m: dist(S.member_state(par.at(p0, value), family, m)))

        def critical(v):
            p = par.at(p0, v)
            s = S.member_state(p, family, member)
            ev = mp.eig(R.jacobian(p, list(s) + [mpf(0)] * 4), left=False, right=False)
            return min((mpc(z) for z in ev), key=lambda z: abs(z - mpc(0, printed_w))), p, s
        v = mp.findroot(lambda x: critical(x)[0].real, (mpf(value) * (1 - mpf(10) ** -12),
                                                         mpf(value) * (1 + mpf(10) ** -12)), solver="secant")
        lam, p, s = critical(v)
        return p, s, lam.imag, v


def check_gh(a, rows):
    """GH rows of the boundary CSV against the reference zero of l1 along the Hopf curve."""
    p0 = R.load_scene(a.scene, a.set)
    par, par2 = S.Param(p0, a.param), S.Param(p0, a.param2)
    checked, ok = 0, True
    for r in rows:
        if r["label"] != "GH":
            continue
        v2_0, v_0, w_0 = mpf(r[a.param2]), mpf(r[a.param]), mpf(r["frequency"])
        printed = [mpf(r[k]) for k in ("q1", "q2", "beta1", "beta2")]
        family = r["family"].strip()
        last = {}

        def l1_at(v2):
            p2 = par2.at(p0, v2)
            p, state, w, v = relocate(p2, par, family, last.get("v", v_0), printed, last.get("w", w_0))
            last.update(v=v, w=w)
            return S.first_lyapunov(p, state, w)[0]
        with mp.workdps(40):
            v2 = mp.findroot(l1_at, (v2_0 * (1 - mpf(10) ** -6), v2_0 * (1 + mpf(10) ** -6)), solver="secant",
                             tol=mpf(10) ** -30)
        l1_at(v2)
        e1 = abs(mpf(r[a.param]) - last["v"]) / abs(last["v"])
        e2 = abs(v2_0 - v2) / abs(v2)
        good = e1 <= a.rtol and e2 <= a.rtol
        ok &= good
        checked += 1
        print(f"{'ok  ' if good else 'FAIL'} GH at {a.param} = {r[a.param]}, {a.param2} = {r[a.param2]}: reference "
              f"({mp.nstr(last['v'], 20)}, {mp.nstr(v2, 20)}), rel diff {float(e1):.1e}, {float(e2):.1e}")
    if checked == 0:
        print("FAIL: no GH row to check")
        return 1
    return 0 if ok else 1


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("binary")
    ap.add_argument("scene")
    ap.add_argument("param")
    ap.add_argument("to")
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE")
    ap.add_argument("--rtol", type=float, default=1e-8)
    ap.add_argument("--min-digits", type=float, default=12.0)
    ap.add_argument("--param2")
    ap.add_argument("--to2")
    a = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [a.binary, "continue", a.scene, "--param", a.param, "--to", a.to, "--no-chart", "-o", tmp]
        for s in a.set:
            cmd += ["--set", s]
        if a.param2:
            cmd += ["--param2", a.param2, "--to2", a.to2]
        run = subprocess.run(cmd, capture_output=True, text=True)
        if run.returncode != 0:
            print(f"FAIL: {' '.join(cmd)} exited {run.returncode}:\n{run.stderr}")
            return 1
        name = f"boundary_{a.param}_{a.param2}.csv" if a.param2 else f"special_{a.param}.csv"
        with open(os.path.join(tmp, name)) as fh:
            text = fh.read()
    rows = list(csv.DictReader(line for line in text.splitlines() if not line.startswith("#")))
    # the arguments but the binary, and the CSV, key the verdict cache (verdict_cache.py)
    cache_key = verdict_cache.key(argv[1:], [text])
    if verdict_cache.recorded(cache_key):
        return 0
    rc = check_gh(a, rows) if a.param2 else check_hopf_points(a, rows)
    if rc == 0:
        verdict_cache.record(cache_key)
    return rc


def check_hopf_points(a, rows):
    p0 = R.load_scene(a.scene, a.set)
    par = S.Param(p0, a.param)
    checked, ok = 0, True
    for r in rows:
        if r["label"] != "HB" or r["converged"].strip() != "1":
            continue
        printed = [mpf(r[k]) for k in ("q1", "q2", "beta1", "beta2")]
        p, state, w, v = relocate(p0, par, r["family"].strip(), mpf(r[a.param]), printed, mpf(r["frequency"]))
        got = float(r["lyapunov"])
        ref, digits = S.first_lyapunov(p, state, w)
        rel = abs(mpf(got) - ref) / abs(ref)
        good = rel <= a.rtol and digits >= a.min_digits
        ok &= good
        checked += 1
        kind = "subcritical" if ref > 0 else "supercritical"
        print(f"{'ok  ' if good else 'FAIL'} HB {r['family']} {a.param} = {r[a.param]}: l1 = {got!r}, "
              f"reference {mp.nstr(ref, 20)} ({digits:.0f} digits, {kind}; Hopf point located again: "
              f"{a.param} = {mp.nstr(v, 20)}), rel diff {float(rel):.1e}")
        if got != 0 and (got > 0) != (ref > 0):
            print("FAIL: sub/supercritical verdict differs")
            ok = False
    if checked == 0:
        print("FAIL: no converged HB row to check")
        return 1
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
