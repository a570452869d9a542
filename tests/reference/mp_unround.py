#!/usr/bin/python3
"""Independent reference for the unround race (docs/model.md §11): every equilibrium of
a scene with a [race] table, to 40 digits, compared with `stability-scan equilibria
--format json`.

Independent of the C++ code: the static conditions are written from the force balance
(rotor: (k - M w^2 + i c w) q = w^2 (U + sum m_i p_i); ball: the tangential component of
the centrifugal force on the ball's centre vanishes, Re(conj(p_i') (q + p_i)) = 0), with
p_i' taken by mpmath's numerical differentiation of p_i(beta) = l_i(beta) e^{i beta}
(no hand-derived derivative), and the search is a dense grid of Newton starts in floats
(G = 8 (k_max + 1) per angle for two balls, 4 (k_max + 1) for three) followed by a
40-digit polish. It finds the equilibria; then each C++ equilibrium must match one, and
each reference one a C++ one: beta to 1e-9 rad and |q| to rtol relative.

  mp_unround.py BINARY SCENE [--rtol 1e-8] [--sweep-factor F]      exit 0 pass, 1 mismatch, 2 misuse

With --sweep-factor F every amplitude of the scene's race is multiplied by F (the
unroundness factor of model.md §11.10) and the program's equilibria are those of
`stability-scan sweep SCENE --param unroundness --from F --to F --steps 1` (sweep_unroundness.csv)
instead of `equilibria`: one point of an unroundness sweep checked independently.
"""
import cmath
import json
import math
import subprocess
import sys
import tomllib

import mpmath as mp

import verdict_cache

mp.mp.dps = 40
FACTOR = mp.mpf(1)  # --sweep-factor


def harmonics_of(scene, n):
    """Centre-path harmonics per ball, as docs/model.md §11.1 and the scene rules say."""
    race = scene.get("race", {})
    balls = scene_balls(scene)
    out = []
    for i in range(n):
        spec, surface = None, False
        for key in ("unroundness", "surface_unroundness"):
            if key in race:
                spec, surface = race[key], key.startswith("surface")
        for b in race.get("ball", []):
            if b["ball"] == i + 1:
                for key in ("unroundness", "surface_unroundness"):
                    if key in b:
                        spec, surface = b[key], key.startswith("surface")
        spec = spec or []
        l, r = balls[i]["race_radius"], balls[i]["radius"]
        conv = (l + r) / l if surface else 1.0
        out.append([(h["order"], mp.mpf(h["amplitude"]) * conv * FACTOR, mp.mpf(h.get("phase", 0))) for h in spec])
    return out


def scene_balls(scene):
    if "ball" in scene:
        return scene["ball"]
    ring = scene["balls"]
    return [dict(ring) for _ in range(ring["count"])]


def path(h, l, beta, lib):
    """l(beta): the exactly offset circle (order 1) times 1 + sum_{k>=2} eps cos(k beta - phi)."""
    e = l
    f = 1
    for k, eps, phi in h:
        if k == 1:
            d = l * eps
            x = beta - phi
            e = d * lib.cos(x) + lib.sqrt(l * l - d * d * lib.sin(x) ** 2)
        else:
            f += eps * lib.cos(k * beta - phi)
    return e * f


def build(scene):
    balls = scene_balls(scene)
    n = len(balls)
    rot = scene["rotor"]
    w = scene["speed"]["omega"]
    masses = [b["mass"] for b in balls]
    M = rot["mass"] + sum(masses)
    H = harmonics_of(scene, n)
    ls = [b["race_radius"] for b in balls]

    def residual(beta, lib, cplx):
        dyn = cplx(rot["stiffness"] - M * w * w, rot["damping"] * w)
        ps = [path(H[i], ls[i], beta[i], lib) * lib.expj(beta[i]) if lib is mp else
              path(H[i], ls[i], beta[i], lib) * cmath.exp(1j * beta[i]) for i in range(n)]
        W = rot["unbalance"] + sum(masses[i] * ps[i] for i in range(n))
        q = w * w * W / dyn
        g = []
        for i in range(n):
            if lib is mp:
                dp = mp.diff(lambda b: path(H[i], ls[i], b, mp) * mp.expj(b), beta[i])
            else:
                # complex step on the real l(beta): exact to rounding, no step-size error
                ell = path(H[i], ls[i], beta[i], math)
                dl = path(H[i], ls[i], complex(beta[i], 1e-30), cmath).imag / 1e-30
                dp = (dl + 1j * ell) * cmath.exp(1j * beta[i])
            g.append(((dp.conjugate() * (q + ps[i])).real) / (ls[i] ** 2))
        return g, q

    kmax = max([k for h in H for k, _, _ in h] + [1])
    return n, residual, kmax


def solve(A, b):
    """Gaussian elimination with partial pivoting in floats; None if singular."""
    n = len(b)
    A = [row[:] + [b[i]] for i, row in enumerate(A)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(A[r][c]))
        if abs(A[p][c]) < 1e-300:
            return None
        A[c], A[p] = A[p], A[c]
        for r in range(c + 1, n):
            f = A[r][c] / A[c][c]
            for k in range(c, n + 1):
                A[r][k] -= f * A[c][k]
    x = [0.0] * n
    for r in reversed(range(n)):
        x[r] = (A[r][n] - sum(A[r][k] * x[k] for k in range(r + 1, n))) / A[r][r]
    return x


def float_newton(residual, beta):
    for _ in range(60):
        g, _ = residual(beta, math, complex)
        n = len(beta)
        J = []
        h = 1e-7
        for j in range(n):
            bp = list(beta)
            bp[j] += h
            gp, _ = residual(bp, math, complex)
            J.append([(gp[i] - g[i]) / h for i in range(n)])
        step = solve([[J[j][i] for j in range(n)] for i in range(n)], g)
        if step is None:
            return None
        beta = [beta[i] - float(step[i]) for i in range(n)]
        if max(abs(s) for s in step) < 1e-11:
            return [b % (2 * math.pi) for b in beta]
    return None


def polish(residual, beta):
    f = lambda *b: residual(list(b), mp, mp.mpc)[0]
    root = mp.findroot(f, [mp.mpf(b) for b in beta], tol=mp.mpf(10) ** -34)
    root = [r if not isinstance(root, mp.mpf) else root for r in (root if hasattr(root, "__len__") else [root])]
    beta = [mp.mpf(r) % (2 * mp.pi) for r in root]
    _, q = residual(beta, mp, mp.mpc)
    return beta, q


def torus_distance(a, b):
    return max(min(abs(x - y) % (2 * math.pi), 2 * math.pi - abs(x - y) % (2 * math.pi)) for x, y in zip(a, b))


def sweep_point(binary, scene_path, factor, n):
    """The equilibria at the first value of a one-value unroundness sweep, as dicts, and the
    CSV's text."""
    import csv
    import tempfile
    with tempfile.TemporaryDirectory() as work:
        out = subprocess.run([binary, "sweep", scene_path, "--param", "unroundness", "--from", factor, "--to", factor,
                              "--steps", "1", "--no-chart", "-o", work], capture_output=True, text=True)
        if out.returncode != 0:
            print(f"stability-scan failed ({out.returncode}): {out.stderr}", file=sys.stderr)
            return None, None
        with open(f"{work}/sweep_unroundness.csv") as fh:
            text = fh.read()
    rows = list(csv.DictReader(line for line in text.splitlines() if not line.startswith("#")))
    # --steps 1 gives the value twice (both ends): the first value's rows are the leading
    # run of increasing equilibrium numbers.
    first = []
    for r in rows:
        if first and int(r["equilibrium"]) <= int(first[-1]["equilibrium"]):
            break
        first.append(r)
    return [{"beta": [float(r[f"beta{i + 1}"]) for i in range(n)], "q1": r["q1"], "q2": r["q2"], "q_abs": r["q_abs"]}
            for r in first], text


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    binary, scene_path = argv[1], argv[2]
    rtol = float(argv[argv.index("--rtol") + 1]) if "--rtol" in argv else 1e-8
    factor = argv[argv.index("--sweep-factor") + 1] if "--sweep-factor" in argv else None
    if factor is not None:
        global FACTOR
        FACTOR = mp.mpf(factor)
    with open(scene_path, "rb") as fh:
        scene = tomllib.load(fh)
    n, residual, kmax = build(scene)
    # the program first: its output keys the verdict cache (verdict_cache.py)
    if factor is None:
        out = subprocess.run([binary, "equilibria", scene_path, "--format", "json"], capture_output=True, text=True)
        if out.returncode != 0:
            print(f"stability-scan failed ({out.returncode}): {out.stderr}", file=sys.stderr)
            return 1
        got, text = json.loads(out.stdout)["equilibria"], out.stdout
    else:
        got, text = sweep_point(binary, scene_path, factor, n)
        if got is None:
            return 1
    cache_key = verdict_cache.key(argv[2:], [text])
    if verdict_cache.recorded(cache_key):
        return 0
    G = (8 if n == 2 else 4) * (kmax + 1)
    found = []
    grid = [(i + 0.5) * 2 * math.pi / G for i in range(G)]
    starts = [[a, b] for a in grid for b in grid] if n == 2 else [[a, b, c] for a in grid for b in grid for c in grid]
    for s in starts:
        z = float_newton(residual, s)
        if z and not any(torus_distance(z, f) < 1e-7 for f in found):
            found.append(z)
    ref = [polish(residual, z) for z in found]

    bad = 0
    print(f"{scene_path}: reference {len(ref)} equilibria, stability-scan {len(got)}")
    if len(ref) != len(got):
        print("  count differs")
        bad += 1
    for beta, q in ref:
        fb = [float(b) for b in beta]
        match = [e for e in got if torus_distance(e["beta"], fb) < 1e-9]
        qa = abs(q)
        if not match:
            print(f"  reference equilibrium beta={fb} |q|={mp.nstr(qa, 12)} not found")
            bad += 1
            continue
        e = match[0]
        err = abs(mp.mpf(e["q_abs"]) - qa) / qa if qa != 0 else abs(mp.mpf(e["q_abs"]))
        eq = abs(mp.mpc(e["q1"], e["q2"]) - q) / abs(q)
        status = "ok " if err <= rtol and eq <= rtol else "BAD"
        if status == "BAD":
            bad += 1
        print(f"  {status} beta={[round(b, 6) for b in fb]} |q|={mp.nstr(qa, 12)} rel.err |q| {float(err):.1e}, q {float(eq):.1e}")
    for e in got:
        if not any(torus_distance(e["beta"], [float(b) for b in beta]) < 1e-9 for beta, _ in ref):
            print(f"  stability-scan equilibrium beta={e['beta']} not in the reference")
            bad += 1
    if not bad:
        verdict_cache.record(cache_key)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
