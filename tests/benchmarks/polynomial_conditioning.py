#!/usr/bin/python3
"""Why the map's degree-(2n+4) characteristic-polynomial path stays two balls (model.md §13.8).

For the aligned equilibrium `+...+` member 1 of a scene with n balls, the analyzer's
refined eigenvalues (`stability-scan equilibria --format csv`; accurate to 1e-8 of their
modulus, checked against mpmath) give the exact monic polynomial of that spectrum,
expanded at 80 digits. Each coefficient is then perturbed by one rounding of long
double (relative 2^-64, random sign: the best any expansion in long double can do),
the roots recomputed at 80 digits, and the worst change of an eigenvalue relative to
its own modulus, and of a real part relative to |Re|, printed (median over 5 draws).
A real part that moves by more than itself means the sign, the stability verdict, is
not determined by long-double coefficients.

    polynomial_conditioning.py BINARY RING_SCENE [--counts 2,3,4,6] [--set omega=900]
"""
import argparse
import csv
import io
import random
import statistics
import subprocess
import tempfile

import mpmath as mp

mp.mp.dps = 80


def spectrum(binary, scene, n, sets):
    text = open(scene).read().replace("count = 11 ", f"count = {n} ", 1)
    with tempfile.NamedTemporaryFile("w", suffix=".toml") as f:
        f.write(text)
        f.flush()
        cmd = [binary, "equilibria", f.name, "--format", "csv"]
        for s in sets:
            cmd += ["--set", s]
        out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    rows = list(csv.DictReader(io.StringIO("\n".join(l for l in out.splitlines() if not l.startswith("#")))))
    row = next(r for r in rows if r["family"] != "balanced" and r["pattern"] == "+" * n and r["member"] == "1")
    d = 2 * n + 4
    return [mp.mpc(row[f"re{k}"], row[f"im{k}"]) for k in range(1, d + 1)]


def coefficients(roots):
    c = [mp.mpc(1)]
    for r in roots:
        c = [a - r * b for a, b in zip(c + [0], [0] + c)]
    return c  # c[0] = 1 (leading) .. c[d] = constant


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("binary")
    ap.add_argument("scene")
    ap.add_argument("--counts", default="2,3,4,6")
    ap.add_argument("--set", action="append", default=[])
    a = ap.parse_args()
    rng = random.Random(1)
    print("n  degree  coefficient span  worst |dlambda|/|lambda|  worst |dRe|/|Re|  (coefficients perturbed by 2^-64)")
    for n in (int(v) for v in a.counts.split(",")):
        lam = spectrum(a.binary, a.scene, n, a.set)
        c = coefficients(lam)
        c = [mp.re(v) for v in c]  # real polynomial
        mags = [abs(v) for v in c if v != 0]
        span = mp.log10(max(mags) / min(mags))
        rel, rre = [], []
        for _ in range(5):
            pert = [v * (1 + rng.choice((-1, 1)) * mp.mpf(2) ** -64) for v in c]
            got = mp.polyroots(pert, maxsteps=400, extraprec=400)
            worst = worst_re = mp.mpf(0)
            for l in lam:
                g = min(got, key=lambda z: abs(z - l))
                worst = max(worst, abs(g - l) / abs(l))
                if mp.re(l) != 0:
                    worst_re = max(worst_re, abs(mp.re(g) - mp.re(l)) / abs(mp.re(l)))
            rel.append(worst)
            rre.append(worst_re)
        print(f"{n:<2} {2 * n + 4:>6}  {float(span):>10.1f} dec  {float(statistics.median(rel)):>18.2e}  "
              f"{float(statistics.median(rre)):>16.2e}")


if __name__ == "__main__":
    main()
