#!/usr/bin/env python3
"""mpmath reference for LuGre friction (docs/model.md §12), independent of the C++ code.

The mechanical part (A(beta), b(s, sdot) with F = 0) is mp_reference_n.py's, itself checked
against central differences and the two-ball reference; this file adds the LuGre force
(12.1)-(12.3) and the bristle states, and computes the Jacobian of the (3n + 4) field by
differences in mpmath at WORK_DPS digits: central differences (step 1e-40 of the
component's size: truncation ~1e-80, rounding 1e-(dps-40)) for every smooth column, and at
a ball at rest (v_i = 0) the one-sided difference of the chosen side in that ball's v_i
column (truncation O(step^2) there, since g is even in v and |v| is linear on each side).
No formula of §12.4-§12.5 is used, so the reference checks them.

Eigenvalues: mp.eig of the scaled Jacobian; the n of smallest modulus must be < 1e-30
max|lambda| (the zeros along the family) and are set aside; the other 2n + 4 are the normal
spectrum.

Usage:
  mp_lugre.py SCENE [--at-balls B1,..,BN]           print the reference rows
  mp_lugre.py --compare CSV SCENE [--rtol 1e-8]     check `equilibria --format csv` output
  mp_lugre.py --compare-sweep CSV SCENE [--rtol R]  check `sweep --param omega` output (model.md
                                                    §12.8): each value's block as --compare at it
Compare checks (why the tolerances: see tests/reference/README.md, "LuGre"):
  * aligned rows: exactly the reference's aligned equilibria (count per pattern and member),
    each state to 1e-10 of the displacement scale / 1e-9 rad; balanced rows: on B
    (|W| <= 1e-12 (U + sum m l)); z = 0 and side 'both' on every such row;
  * stuck rows: q, z from the printed betas to 1e-10 relative; load = tau/mu_s to 1e-10;
  * every row: the 2n + 4 normal eigenvalues each to rtol of its modulus, n_zero = n and
    n trailing 0,0 pairs; side_stable agrees with the sign of the reference abscissa
    (unless within rtol of 0); stable = both sides stable; non_smooth = sides differ.
Exit 0 pass, 1 fail, 2 bad input.
"""
import argparse
import csv
import math
import os
import sys
import tomllib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mp_reference_n as ref  # noqa: E402  (sets mp.dps to its working precision)
from mpmath import mp, mpf, mpc  # noqa: E402

WORK_DPS = 90
mp.dps = WORK_DPS
LUGRE_KEYS = ("sigma0", "sigma1", "sigma2", "mu_c", "mu_s", "v_s")


class Lugre:
    """Per-ball LuGre coefficients as IEEE doubles (mpf(float) when used)."""

    def __init__(self, values):
        self.sigma0, self.sigma1, self.sigma2, self.mu_c, self.mu_s, self.v_s = (float(values[k]) for k in LUGRE_KEYS)


def load(path, omega=None):
    """A LuGre scene with [[ball]] tables (per-ball LuGre keys override [friction]'s);
    omega: the value of `--set omega=V` (the double the C++ parses)."""
    with open(path, "rb") as fh:
        doc = tomllib.load(fh)
    fr = doc["friction"]
    if fr.get("law") != "lugre":
        raise ref.InputError(f"{path}: friction law is not 'lugre'")
    if "ball" not in doc:
        raise ref.InputError(f"{path}: the LuGre reference reads [[ball]] tables only")
    rolling = bool(doc.get("rolling", True))
    balls, lugre = [], []
    for bt in doc["ball"]:
        balls.append(ref.Ball(bt["mass"], bt["race_radius"], bt["radius"], bt.get("rolling", rolling)))
        lugre.append(Lugre({k: bt.get(k, fr.get(k)) for k in LUGRE_KEYS}))
    r = doc["rotor"]
    p = ref.Params(r["mass"], r["stiffness"], r.get("damping", 0.0), r["unbalance"], doc["speed"]["omega"] if omega is None else omega, balls,
                   "none", None, source=str(path))
    p.lugre = lugre
    return p


def level(b, v):
    x = v / mpf(b.v_s)
    return mpf(b.mu_c) + (mpf(b.mu_s) - mpf(b.mu_c)) * mp.exp(-x * x)             # (12.1)


def bristle_rate(b, v, z):
    return v - mpf(b.sigma0) * abs(v) * z / level(b, v)                            # (12.2)


def field(p, x):
    n = p.n
    d = n + 2
    w = mpf(p.omega)
    xs = list(x[:2 * d])
    b = ref.rhs(p, xs)                                   # law none: F = 0
    for i in range(n):
        lb = p.lugre[i]
        v, z = x[d + 2 + i], x[2 * d + i]
        N = mpf(p.balls[i].m) * mpf(p.balls[i].l) * w * w
        F = -N * (mpf(lb.sigma0) * z + mpf(lb.sigma1) * bristle_rate(lb, v, z) + mpf(lb.sigma2) * v)   # (12.3)
        b[2 + i] += mpf(p.balls[i].l) * F
    A = ref.mass_matrix(p, xs[2:d])
    sdd = mp.lu_solve(A, mp.matrix(b))
    return xs[d:] + [sdd[k] for k in range(d)] + [bristle_rate(p.lugre[i], x[d + 2 + i], x[2 * d + i])
                                                  for i in range(n)]


def sizes(p):
    n = p.n
    d = n + 2
    qs = p.capacity() / p.M()
    w = mpf(p.omega)
    out = [qs, qs] + [mpf(1)] * n + [qs * w, qs * w] + [w] * n
    out += [mpf(p.lugre[i].mu_s) / mpf(p.lugre[i].sigma0) for i in range(n)]
    assert len(out) == 3 * n + 4 and d
    return out


def jacobian(p, x, side):
    """Differences of `field` (see the module doc); side +1 forward, -1 backward."""
    n = p.n
    d = n + 2
    m = 3 * n + 4
    sc = sizes(p)
    J = mp.zeros(m, m)
    f0 = None
    for k in range(m):
        h = sc[k] * mpf(10) ** -40
        at_rest_v = d + 2 <= k < 2 * d and x[k] == 0
        if at_rest_v:
            if f0 is None:
                f0 = field(p, x)
            xp = list(x)
            xp[k] += side * h
            fp = field(p, xp)
            col = [(fp[r] - f0[r]) / (side * h) for r in range(m)]
        else:
            xp, xm = list(x), list(x)
            xp[k] += h
            xm[k] -= h
            fp, fm = field(p, xp), field(p, xm)
            col = [(fp[r] - fm[r]) / (2 * h) for r in range(m)]
        for r in range(m):
            J[r, k] = col[r]
    return J


def equilibrium(p, betas, zero_bristle):
    """x = (q(beta), beta, 0, z) with sigma0 z = -tau (12.5), or z = 0."""
    n = p.n
    q = ref.q_of(p, betas)
    x = [q.real, q.imag] + list(betas) + [mpf(0)] * (n + 2)
    for i in range(n):
        tau = (q.real * mp.sin(betas[i]) - q.imag * mp.cos(betas[i])) / mpf(p.balls[i].l)
        x.append(mpf(0) if zero_bristle else -tau / mpf(p.lugre[i].sigma0))
    return x


def load_ratios(p, x):
    n = p.n
    return [(x[0] * mp.sin(x[2 + i]) - x[1] * mp.cos(x[2 + i])) / mpf(p.balls[i].l) / mpf(p.lugre[i].mu_s)
            for i in range(n)]


def normal_spectrum(p, x, side):
    """(normal eigenvalues sorted, the n set-aside zeros, field residual at x)."""
    n = p.n
    f = field(p, x)
    sc = sizes(p)
    w2 = mpf(p.omega) ** 2
    res = max(abs(f[k]) / (sc[k] * w2) for k in range(len(f)))
    J = jacobian(p, x, side)
    ev = ref.eigenvalues(J, sc)
    by_mod = sorted(ev, key=abs)
    big = max(abs(z) for z in ev)
    zeros = by_mod[:n]
    if max(abs(z) for z in zeros) > mpf(10) ** -30 * big:
        raise RuntimeError(f"the {n} smallest eigenvalues are not zeros: {[mp.nstr(z, 5) for z in zeros]}")
    normal = ref.sort_eigenvalues(by_mod[n:])
    return normal, zeros, res


def reference_rows(p, at_balls=None):
    """The z = 0 aligned equilibria (exact), one balanced point if B exists, and a stuck state."""
    rows = []
    for a in ref.aligned_equilibria(p):
        rows.append((a.family(p.n), a.pattern, a.member, equilibrium(p, a.betas, True), True))
    if at_balls is not None:
        rows.append(("stuck", "", 1, equilibrium(p, [mpf(b) for b in at_balls], False), False))
    return rows


def print_rows(p, rows):
    for fam, pat, mem, x, zb in rows:
        for side in ((1,) if zb else (1, -1)):
            normal, zeros, res = normal_spectrum(p, x, side)
            print(f"{fam} {pat} {mem} side {'both' if zb else ('forward' if side > 0 else 'backward')}: "
                  f"residual {mp.nstr(res, 3)}, load {[mp.nstr(r, 6) for r in load_ratios(p, x)]}")
            for z in normal:
                print(f"   {mp.nstr(z.real, 20):>30} {mp.nstr(z.imag, 20):>30}")


# ------------------------------------------------------------------------------ compare
def compare(csv_path, p, rtol):
    n = p.n
    d = n + 2
    with open(csv_path) as fh:
        lines = [ln for ln in fh if not ln.startswith("#")]
    table = list(csv.DictReader(lines))
    if not table:
        raise ref.InputError(f"{csv_path}: no rows")
    if f"beta{n}" not in table[0] or f"beta{n + 1}" in table[0]:
        raise ref.InputError(f"{csv_path}: not a {n}-ball LuGre CSV")
    fails = []
    aligned = ref.aligned_equilibria(p)
    qscale = p.capacity() / p.M()
    seen_aligned = []
    states = {}
    for idx, row in enumerate(table, 1):
        tag = f"row {idx} ({row['family']} {row['pattern']} {row['member']} {row['side']})"
        betas_prog = [mpf(float(row[f'beta{i}'])) for i in range(1, n + 1)]
        q_prog = [mpf(float(row['q1'])), mpf(float(row['q2']))]
        z_prog = [mpf(float(row[f'z{i}'])) for i in range(1, n + 1)]
        fam = row["family"]
        if fam == "stuck":
            zb = False
            x = equilibrium(p, betas_prog, False)
            if row["side"] not in ("forward", "backward"):
                fails.append(f"{tag}: a stuck row has side forward or backward")
        else:
            zb = True
            if row["side"] != "both":
                fails.append(f"{tag}: a z = 0 row has side 'both'")
            if any(z != 0 for z in z_prog):
                fails.append(f"{tag}: z must be exactly 0 on a z = 0 row")
            if fam == "balanced":
                betas, ok = ref.polish_onto_B(p, betas_prog)
                if not ok:
                    fails.append(f"{tag}: the printed angles do not polish onto the balanced set")
                W = ref.W_of(p, betas_prog)
                if abs(W) > mpf("1e-12") * p.capacity():
                    fails.append(f"{tag}: |W(beta)| = {mp.nstr(abs(W), 3)} is not on the balanced set")
            else:
                cands = [a for a in aligned if a.pattern == row["pattern"] and a.member == int(row["member"])]
                if len(cands) != 1:
                    fails.append(f"{tag}: no reference aligned equilibrium with this pattern and member")
                    continue
                betas = cands[0].betas
                seen_aligned.append((row["pattern"], int(row["member"])))
            x = equilibrium(p, betas, True)
            for i in range(n):
                if ref.angdist(betas[i], betas_prog[i]) > mpf("1e-9"):
                    fails.append(f"{tag}: beta{i + 1} off the reference by {mp.nstr(ref.angdist(betas[i], betas_prog[i]), 3)}")
        for k in range(2):
            if abs(q_prog[k] - x[k]) > mpf("1e-10") * (qscale + abs(mpc(x[0], x[1]))):
                fails.append(f"{tag}: q{k + 1} = {mp.nstr(q_prog[k], 12)} against {mp.nstr(x[k], 12)}")
        for i in range(n):
            zr = x[2 * d + i]
            zs = mpf(p.lugre[i].mu_s) / mpf(p.lugre[i].sigma0)
            if abs(z_prog[i] - zr) > mpf("1e-10") * zs:
                fails.append(f"{tag}: z{i + 1} = {mp.nstr(z_prog[i], 12)} against {mp.nstr(zr, 12)}")
        side = -1 if row["side"] == "backward" else 1
        normal, zeros, res = normal_spectrum(p, x, side)
        if res > mpf(10) ** -60:
            fails.append(f"{tag}: the reference state is not an equilibrium of the reference field ({mp.nstr(res, 3)})")
        if int(row["n_zero"]) != n:
            fails.append(f"{tag}: n_zero = {row['n_zero']}, expected {n}")
        got = []
        for k in range(1, 3 * n + 5):
            got.append(mpc(mpf(float(row[f're{k}'])), mpf(float(row[f'im{k}']))))
        if any(z != 0 for z in got[2 * n + 4:]):
            fails.append(f"{tag}: the last {n} eigenvalues must be the zeros 0,0")
        prog = got[:2 * n + 4]
        unused = list(normal)
        for lam in sorted(prog, key=lambda z: -abs(z)):
            j = min(range(len(unused)), key=lambda t: abs(unused[t] - lam))
            r = unused.pop(j)
            if abs(r - lam) > rtol * abs(r):
                fails.append(f"{tag}: eigenvalue {mp.nstr(lam, 15)} against {mp.nstr(r, 20)} "
                             f"(relative {mp.nstr(abs(r - lam) / abs(r), 3)})")
        ab = max(z.real for z in normal)
        lam_ab = max(normal, key=lambda z: z.real)
        if abs(ab) > rtol * abs(lam_ab):
            want = 1 if ab < 0 else 0
            if int(row["side_stable"]) != want:
                fails.append(f"{tag}: side_stable = {row['side_stable']} but the reference abscissa is {mp.nstr(ab, 10)}")
        states.setdefault((fam, row["pattern"], row["member"]), []).append(row)
    for key, rows in states.items():
        sides = [int(r["side_stable"]) for r in rows]
        for r in rows:
            if int(r["stable"]) != int(all(sides)):
                fails.append(f"{key}: stable = {r['stable']} but the sides give {sides}")
            if int(r["non_smooth"]) != int(len(set(sides)) > 1):
                fails.append(f"{key}: non_smooth = {r['non_smooth']} but the sides give {sides}")
    want = sorted((a.pattern, a.member) for a in aligned)
    if sorted(seen_aligned) != want:
        fails.append(f"aligned rows {sorted(seen_aligned)} against the reference's {want}")
    has_bal = any(r["family"] == "balanced" for r in table)
    if has_bal != bool(ref.B_exists(p)):
        fails.append(f"balanced rows present: {has_bal}, balanced set exists: {ref.B_exists(p)}")
    return fails, len(table)


def compare_sweep(csv_path, scene, rtol):
    """`sweep --param omega` of a LuGre scene: the rows of each omega, without the first
    column, are an `equilibria` CSV at that omega (the value printed with 17 digits, so
    float() gives the double the program used); each block is compared as --compare."""
    import tempfile
    with open(csv_path) as fh:
        lines = [ln for ln in fh if not ln.startswith("#")]
    if not lines or not lines[0].startswith("omega,"):
        raise ref.InputError(f"{csv_path}: not a LuGre sweep of omega (first column omega)")
    head = lines[0].split(",", 1)[1]
    blocks = {}
    for ln in lines[1:]:
        value, rest = ln.split(",", 1)
        blocks.setdefault(value, []).append(rest)
    fails, count = [], 0
    for value, rows in blocks.items():
        with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as tmp:
            tmp.write(head + "".join(rows))
        try:
            f, c = compare(tmp.name, load(scene, float(value)), rtol)
        finally:
            os.unlink(tmp.name)
        fails += [f"omega={value}: {x}" for x in f]
        count += c
    return fails, count, len(blocks)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", nargs="?")
    ap.add_argument("--compare", metavar="CSV")
    ap.add_argument("--compare-sweep", metavar="CSV")
    ap.add_argument("--at-balls")
    ap.add_argument("--rtol", type=float, default=1e-8)
    ap.add_argument("--set", dest="overrides", action="append", default=[], help="omega=V only")
    a = ap.parse_args()
    try:
        omega = None
        for ov in a.overrides:
            name, _, value = ov.partition("=")
            if name.strip() != "omega":
                raise ref.InputError(f"--set {ov}: the LuGre reference overrides omega only")
            omega = float(value)
        if a.compare_sweep:
            if not a.scene:
                raise ref.InputError("--compare-sweep CSV SCENE")
            fails, count, values = compare_sweep(a.compare_sweep, a.scene, mpf(a.rtol))
            for f in fails:
                print("FAIL", f)
            print(f"{'FAIL' if fails else 'PASS'}: {count} rows at {values} values of {a.compare_sweep} against the "
                  f"LuGre reference ({WORK_DPS} digits, rtol {a.rtol})")
            return 1 if fails or values < 2 else 0
        if a.compare:
            if not a.scene:
                raise ref.InputError("--compare CSV SCENE")
            p = load(a.scene, omega)
            fails, count = compare(a.compare, p, mpf(a.rtol))
            for f in fails:
                print("FAIL", f)
            print(f"{'FAIL' if fails else 'PASS'}: {count} rows of {a.compare} against the LuGre reference "
                  f"({WORK_DPS} digits, rtol {a.rtol})")
            return 1 if fails else 0
        if not a.scene:
            raise ref.InputError("a scene is required")
        p = load(a.scene, omega)
        at = [float(b) for b in a.at_balls.split(",")] if a.at_balls else None
        print_rows(p, reference_rows(p, at))
        return 0
    except (ref.InputError, KeyError, ValueError, OSError) as ex:
        print(f"mp_lugre.py: {ex}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
