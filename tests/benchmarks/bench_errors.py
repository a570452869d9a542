#!/usr/bin/python3
"""Scores the eigenvalues written by `bench_equilibria eigenvalues OUT.csv SCENE...`
against the independent 40+-digit reference (tests/reference/mp_reference.py).

For every method: the worst relative error |lambda - ref| / |ref| over every eigenvalue
of every equilibrium of every scene, the same for the smallest-modulus eigenvalue alone
(the slow ball modes that decide stability), and the number of equilibria whose
stability verdict (sign of the spectral abscissa) is wrong where the reference's sign
is not itself in doubt (|abscissa| > 1e-8 of that eigenvalue's modulus).

    bench_errors.py EIGENVALUES.csv
"""
import csv
import math
import os
import sys
from collections import defaultdict

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "reference"))
import mpmath as mp  # noqa: E402
import mp_reference as ref  # noqa: E402


def pair(refs, got):
    """Greedy pairing, smallest reference modulus first, by relative distance."""
    free = list(range(len(got)))
    out = {}
    for k in sorted(range(len(refs)), key=lambda i: abs(refs[i])):
        r = refs[k]
        scale = abs(r) if r != 0 else 1
        j = min(free, key=lambda i: abs(got[i] - r) / scale)
        free.remove(j)
        out[k] = got[j]
    return out


def main(path):
    rows = list(csv.DictReader(open(path)))
    by_scene = defaultdict(list)
    for r in rows:
        by_scene[r["scene"]].append(r)
    worst = defaultdict(float)
    worst_small = defaultdict(float)
    wrong = defaultdict(int)
    counted = defaultdict(int)
    for scene, srows in sorted(by_scene.items()):
        p = ref.load_scene(scene)
        eqs = ref.solve(p)
        scale = p.displacement_scale()
        for r in srows:
            cands = [e for e in eqs if e.family == r["family"]]
            if not cands:
                continue
            def dist(e):
                dq = abs(mp.mpf(r["q1"]) - e.q1) + abs(mp.mpf(r["q2"]) - e.q2)
                def angle(a, b):  # each angle wrapped on its own: swapped balls differ by pi twice
                    d = abs(mp.mpf(a) - b) % (2 * mp.pi)
                    return min(d, 2 * mp.pi - d)
                return float(dq / scale + angle(r["beta1"], e.b1) + angle(r["beta2"], e.b2))
            e = min(cands, key=dist)
            got = [complex(float(r[f"re{k}"]), float(r[f"im{k}"])) for k in range(1, 9)]
            refs = [complex(z) for z in e.eig]
            big = max(abs(z) for z in refs)
            paired = pair(refs, got)
            method = r["method"]
            counted[method] += 1
            errs = []
            for k, z in enumerate(refs):
                if abs(z) < 1e-30 * big:  # structural zero (U = 0 sets): measured absolutely
                    errs.append(abs(paired[k]) / big)
                else:
                    errs.append(abs(paired[k] - z) / abs(z))
            worst[method] = max(worst[method], max(errs))
            k_small = min(range(8), key=lambda i: abs(refs[i]) if abs(refs[i]) >= 1e-30 * big else math.inf)
            worst_small[method] = max(worst_small[method], errs[k_small])
            ab = max(z.real for z in refs)
            k_ab = max(range(8), key=lambda i: refs[i].real)
            if abs(ab) > 1e-8 * abs(refs[k_ab]):
                got_ab = max(z.real for z in got)
                if (got_ab < 0) != (ab < 0):
                    wrong[method] += 1
    digits = lambda e: "  inf" if e == 0 else f"{-math.log10(e):5.1f}"
    print(f"{'method':<12} {'equilibria':>10} {'worst rel. error':>17} {'digits':>6} "
          f"{'smallest |lambda|':>18} {'digits':>6} {'wrong stability':>16}")
    for m in ("plain", "dense-qr", "structured", "refined"):
        if m in counted:
            print(f"{m:<12} {counted[m]:>10} {worst[m]:>17.2e} {digits(worst[m])} {worst_small[m]:>18.2e} "
                  f"{digits(worst_small[m])} {wrong[m]:>16}")


if __name__ == "__main__":
    main(sys.argv[1])
