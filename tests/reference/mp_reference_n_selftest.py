#!/usr/bin/python3
"""Self-test of the n-ball reference mp_reference_n.py (run: /usr/bin/python3 THIS; < 60 s).

 1. n = 2: equilibria and eigenvalues equal those of the two-ball reference mp_reference.py
    (imported; closed forms of docs/model.md §5) on four tests/scenes/reference scenes, to
    1e-60; and a CSV written from mp_reference.py's values passes the n-ball compare;
 2. scene loading: the [balls] ring form (total_mass, [[balls.override]]) equals the same
    scene as [[ball]] tables; --set m3= / mu_c2= / l= touch the right balls;
 3. the hand-derived J equals central differences of the full vector field (n = 3, 5);
 4. trace identity: sum(lambda) = trace J to 1e-60 relative (n = 3, 4, 5, aligned and balanced);
 5. c = 0 and friction none: the spectrum is symmetric under lambda -> -lambda (n = 3, 4);
 6. every pattern with two real roots: exactly 2^n isolated equilibria (n = 3, 4), each with a
    static residual < 1e-70, and the grid-started Newton finds the same set;
 7. balanced points: exactly n - 2 structural zeros with viscous friction (n = 3, 4, 5), exactly
    2(n - 2) with friction none (n = 3, 4), 3 for n = 4 with three frictionless balls, all points
    on B, and eig(V_N^T J V_N) equals the normal spectrum (n + 6 values);
 8. stribeck at an equilibrium has the spectrum of coulomb with mu = mu_s (model.md §7);
 9. compare mode: a CSV written from the reference passes; perturbing one eigenvalue by 1e-6
    relative, dropping a row, adding a spurious aligned row, adding a balanced row off B,
    a wrong n_structural_zero, a wrong 'stable' and a swapped member number each fail.
Exit status 0 if all pass.
"""
import copy
import csv
import io
import os
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import mp_reference_n as R  # noqa: E402
import mp_reference as R2  # noqa: E402
from mpmath import mp, mpf, mpc  # noqa: E402

mp.dps = R.WORK_DPS
SCENES2 = os.path.join(ROOT, "tests", "scenes", "reference")
SCENES_N = os.path.join(ROOT, "tests", "scenes", "reference_n")
failures = []


def check(ok, what):
    print(f"  {'ok  ' if ok else 'FAIL'} {what}", flush=True)
    if not ok:
        failures.append(what)


def scene(name):
    return os.path.join(SCENES_N, name + ".toml")


def make_params(n, law="viscous", c=2.0, U=6e-7, omega=900.0, unequal=True, kappa=1e3):
    ms = [3.3e-5, 2.5e-5, 2.0e-5, 2.8e-5, 3.1e-5]
    ls = [0.018, 0.020, 0.019, 0.021, 0.0185]
    balls = []
    for i in range(n):
        m, l = (ms[i], ls[i]) if unequal else (3.3e-5, 0.018)
        balls.append(R.Ball(m, l, 1e-3, True, mu=0.002, d=1e-4, mu_c=0.001, mu_s=0.003, v_s=0.1))
    p = R.Params(0.12, 7500.0, c, U, omega, balls, law, kappa if law in ("coulomb", "stribeck") else None,
                 source=f"selftest n={n} {law}")
    p.check()
    return p


def rel_spectrum_diff(a, b):
    """max relative difference of two sorted spectra (bottleneck pairing if sorting differs)."""
    if len(a) != len(b):
        return mpf(1)
    scale = max(abs(z) for z in a)
    cost = (lambda x, y: float(abs(x - y) / max(abs(x), mpf(10) ** -30 * scale)))
    perm = R._bottleneck_pairing(a, b, cost)
    return max(abs(a[k] - b[perm[k]]) / max(abs(a[k]), mpf(10) ** -30 * scale) for k in range(len(a)))


# ------------------------------------------------------------------------------ 1
def test_two_ball():
    print("1. n = 2 against mp_reference.py")
    for name in ("coulomb_k1e3_w900", "unequal_balls", "viscous_d1e-4", "below_resonance_w150"):
        path = os.path.join(SCENES2, name + ".toml")
        p2, pn = R2.load_scene(path), R.load_scene(path)
        ref2 = R2.solve(p2)
        mine = [(e.family(2), e.state, "aligned", e) for e in R.aligned_equilibria(pn)]
        mine += [("balanced", [mpf(0), mpf(0)] + b, "balanced", None) for b in R.sample_B(pn, 2)]
        same_fams = sorted(e.family for e in ref2) == sorted(m[0] for m in mine)
        worst = mpf(0)
        rows = []
        for e in ref2:
            cand = [m for m in mine if m[0] == e.family]
            best = min(cand, key=lambda m: R.angdist(m[1][2], e.b1) + R.angdist(m[1][3], e.b2))
            r = R.analyse(pn, best[2], best[1])
            ds = max(R.angdist(best[1][2], e.b1), R.angdist(best[1][3], e.b2),
                     mp.hypot(best[1][0] - e.q1, best[1][1] - e.q2) / pn.displacement_scale())
            worst = max(worst, ds, rel_spectrum_diff(e.eig, r.eig))
            rows.append((e, best[3]))
        check(same_fams and worst < mpf(10) ** -60,
              f"{name}: families {'equal' if same_fams else 'DIFFER'}, worst state/eigenvalue difference "
              f"{mp.nstr(worst, 3)}")
        if name == "unequal_balls":
            # a CSV in the n-ball contract from mp_reference.py's own numbers must pass the compare
            buf = io.StringIO()
            w = csv.writer(buf, lineterminator="\n")
            w.writerow(R.csv_header(2))
            bal = 0
            for e, al in rows:
                ab = max(z.real for z in e.eig)
                if e.family == "balanced":
                    bal += 1
                    pat, mem = "", bal
                else:
                    pat, mem = al.pattern, al.member
                row = [e.family, pat, str(mem), repr(float(e.q1)), repr(float(e.q2)), repr(float(e.b1)),
                       repr(float(e.b2)), repr(float(e.residual)), repr(float(ab)), str(int(ab < 0)), "0"]
                for z in e.eig:
                    row += [repr(float(z.real)), repr(float(z.imag))]
                w.writerow(row)
            ok, text = run_compare(buf.getvalue(), pn)
            check(ok, "unequal_balls: CSV from mp_reference.py values passes the n-ball compare")
            if not ok:
                print(text)


# ------------------------------------------------------------------------------ 2
def test_loading():
    print("2. scene loading")
    ring = """
rolling = true
[rotor]
mass = 0.12
stiffness = 7500.0
damping = 2.0
unbalance = 6.0e-7
[balls]
count = 4
total_mass = 1.3e-4
race_radius = 0.018
radius = 1.0e-3
mu = 0.003
[[balls.override]]
ball = 3
mass = 4.0e-5
rolling = false
[[balls.override]]
ball = 4
mu = 0.001
[friction]
law = "coulomb"
mu = 0.002
kappa = 1.0e3
[speed]
omega = 900.0
"""
    m = 1.3e-4 / 4
    tabs = "".join(f"\n[[ball]]\nmass = {mm!r}\nrace_radius = 0.018\nradius = 1.0e-3\nmu = {mu!r}\n"
                   + ("rolling = false\n" if i == 2 else "")
                   for i, (mm, mu) in enumerate([(m, 0.003), (m, 0.003), (4.0e-5, 0.003), (m, 0.001)]))
    table = ring.split("[balls]")[0] + tabs + "[friction]" + ring.split("[friction]")[1]
    with tempfile.TemporaryDirectory() as d:
        a, b = os.path.join(d, "ring.toml"), os.path.join(d, "tables.toml")
        open(a, "w").write(ring)
        open(b, "w").write(table)
        pa, pb = R.load_scene(a), R.load_scene(b)
        same = all(vars(x) == vars(y) for x, y in zip(pa.balls, pb.balls)) and pa.n == pb.n == 4
        check(same and pa.balls[0].m == 1.3e-4 / 4 and not pa.balls[2].rolling and pa.balls[3].mu == 0.001,
              "[balls] ring form (total_mass / count as a double, overrides) equals the [[ball]] tables")
        pc = R.load_scene(a, ["m3=5e-5", "mu2=0.004", "l=0.02", "omega=1000", "M_r=0.2"])
        check(pc.balls[2].m == 5e-5 and pc.balls[0].m == m and pc.balls[1].mu == 0.004 and
              pc.balls[0].mu == 0.003 and all(x.l == 0.02 for x in pc.balls) and pc.omega == 1000.0
              and pc.Mr == 0.2, "--set m3 / mu2 / l / omega / M_r")
        bad = 0
        for ov in ("m5=1e-5", "x=1", "mu_c12=1"):
            try:
                R.load_scene(a, [ov])
            except R.InputError:
                bad += 1
        p12 = copy.deepcopy(pc)
        p12.balls = [copy.deepcopy(pc.balls[0]) for _ in range(12)]
        R.apply_override(p12, "mu_c12=0.5")
        check(bad == 3 and p12.balls[11].mu_c == 0.5 and p12.balls[0].mu_c is None,
              "--set rejects out-of-range and unknown names; two-digit indices (mu_c12)")


# ------------------------------------------------------------------------------ 3-5, 8
def test_jacobian_trace_symmetry():
    print("3. hand-derived J against central differences of the vector field")
    for n, law in ((3, "coulomb"), (5, "stribeck")):
        p = make_params(n, law)
        e = R.aligned_equilibria(p)[1]
        b = R.sample_B(p, 1)[0]
        errs = [R.jacobian_mismatch(p, e.state), R.jacobian_mismatch(p, [0, 0] + b)]
        check(max(errs) < mpf(10) ** -40, f"n = {n} {law}: |J - J_fd| (row-scaled) "
              f"{mp.nstr(errs[0], 3)} aligned, {mp.nstr(errs[1], 3)} balanced")
    print("4. trace identity")
    worst = mpf(0)
    for n, law in ((3, "viscous"), (4, "coulomb"), (5, "stribeck")):
        p = make_params(n, law)
        for kind, st in (("aligned", R.aligned_equilibria(p)[0].state), ("balanced", [0, 0] + R.sample_B(p, 1)[0])):
            worst = max(worst, R.analyse(p, kind, st).trace_err)
    check(worst < mpf(10) ** -60, f"sum(lambda) = trace J, worst {mp.nstr(worst, 3)} (n = 3, 4, 5)")
    print("5. c = 0, friction none: lambda -> -lambda")
    worst = mpf(0)
    for n in (3, 4):
        p = make_params(n, "none", c=0.0)
        for kind, st in (("aligned", R.aligned_equilibria(p)[2].state), ("balanced", [0, 0] + R.sample_B(p, 1)[0])):
            r = R.analyse(p, kind, st)
            scale = max(abs(z) for z in r.eig)
            nz = [z for z in r.eig if abs(z) > mpf(10) ** -30 * scale]
            for z in nz:
                worst = max(worst, min(abs(z + y) for y in nz) / abs(z))
    check(worst < mpf(10) ** -50, f"every eigenvalue has its negative, worst {mp.nstr(worst, 3)}")
    print("8. stribeck = coulomb(mu_s) at an equilibrium")
    ps, pc = make_params(3, "stribeck", kappa=1e4), make_params(3, "coulomb", kappa=1e4)
    for b in pc.balls:
        b.mu = 0.003
    st = R.aligned_equilibria(ps)[3].state
    d = rel_spectrum_diff(R.analyse(ps, "aligned", st).eig, R.analyse(pc, "aligned", st).eig)
    check(d < mpf(10) ** -60, f"n = 3: spectra equal to {mp.nstr(d, 3)}")


# ------------------------------------------------------------------------------ 6
def test_counts():
    print("6. 2^n isolated equilibria when every pattern has two real roots")
    for n in (3, 4):
        p = make_params(n, "viscous")
        K, C = p.KC()
        R_ = mpf(p.U) * mp.hypot(K, C)
        all_two = all(abs(C * sum(p.ml(i) * (1 if ch == "+" else -1) for i, ch in enumerate(pat))) < R_
                      for pat in R.patterns(n))
        eqs = R.aligned_equilibria(p)
        res = max(R.residual_norm(p, e.state) for e in eqs)
        t0 = time.time()
        ms = R.multistart(p)
        check(all_two and len(eqs) == 2 ** n and res < mpf(10) ** -70,
              f"n = {n}: {len(eqs)} = 2^{n} equilibria, worst static residual {mp.nstr(res, 3)}")
        check(not ms["missed"] and not ms["extra"] and ms["found"] == 2 ** n,
              f"n = {n}: multistart ({ms['starts']} starts, {time.time() - t0:.1f} s) finds the same "
              f"{ms['found']} (missed {len(ms['missed'])}, extra {len(ms['extra'])})")
    # and a scene where some patterns have no root (near resonance, C|S| > R for +++):
    p = R.load_scene(scene("n3_near_fold"), ["omega=262"])
    eqs = R.aligned_equilibria(p)
    ms = R.multistart(p)
    check(len(eqs) == 6 and not ms["missed"] and not ms["extra"],
          f"n = 3 past the +++ fold (omega = 262): {len(eqs)} = 6 equilibria, multistart agrees")


# ------------------------------------------------------------------------------ 7
def test_balanced():
    print("7. structural zeros and the normal spectrum on B")
    for n, law, expect in ((3, "viscous", 1), (4, "viscous", 2), (5, "viscous", 3), (3, "none", 2), (4, "none", 4)):
        p = make_params(n, law)
        pts = R.sample_B(p, 2)
        ok = len(pts) == 2
        detail = []
        for b in pts:
            w = abs(R.W_of(p, b)) / p.capacity()
            r = R.analyse(p, "balanced", [0, 0] + b, deflate=True)
            dfl, tv = r.deflated
            dz, dn = R.split_structural(dfl)
            agree = len(dfl) == n + 6 and len(dn) == len(r.normal) and rel_spectrum_diff(dn, r.normal) < mpf(10) ** -40
            scale = max(abs(z) for z in r.eig)
            gap = min(abs(z) for z in r.normal) / scale
            ok = ok and len(r.zeros) == expect == p.structural_zero_count() and agree and w < mpf(10) ** -70
            detail.append(f"{len(r.zeros)} zeros (max {mp.nstr(max(abs(z) for z in r.zeros) / scale, 2)}), "
                          f"smallest normal {mp.nstr(gap, 2)}, deflated {'=' if agree else '!='}")
        check(ok, f"n = {n} {law}: expect {expect}; " + "; ".join(detail))
    # mixed: coulomb with mu = 0 on balls 2..4 of 4: one extra Jordan partner (a tangent
    # vector that moves only frictionless balls exists once three of them are free)
    p = make_params(4, "coulomb")
    for b in p.balls[1:]:
        b.mu = 0.0
    b = R.sample_B(p, 1)[0]
    r = R.analyse(p, "balanced", [0, 0] + b)
    check(len(r.zeros) == 3 == p.structural_zero_count(b),
          f"n = 4 coulomb with mu = 0 on three balls: {len(r.zeros)} zeros = (n - 2) + (3 - 2)")


# ------------------------------------------------------------------------------ 9
def run_compare(text, p, cache=None, **kw):
    with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as fh:
        fh.write(text)
        path = fh.name
    out = io.StringIO()
    try:
        ok = R.compare(path, p, out=out, cache=cache, **kw)
    finally:
        os.unlink(path)
    return ok, out.getvalue()


def test_compare():
    print("9. compare mode on a CSV written from the reference (n = 3 unequal coulomb)")
    p = R.load_scene(scene("n3_unequal_coulomb_k1e3"))
    buf = io.StringIO()
    R.write_csv(p, buf, samples=3)
    good = buf.getvalue()
    lines = good.splitlines()
    header = lines[0].split(",")
    col = {c: k for k, c in enumerate(header)}
    cache = {}
    t0 = time.time()
    ok, text = run_compare("# a comment line\n" + good, p, cache)
    check(ok, f"the reference's own CSV (with a comment line) passes ({time.time() - t0:.1f} s)")
    if not ok:
        print(text)

    def edit(k, **vals):
        rows = [ln.split(",") for ln in lines]
        for key, v in vals.items():
            rows[k][col[key]] = v
        return "\n".join(",".join(r) for r in rows) + "\n"

    def expect_fail(text_, what, needle):
        ok_, out = run_compare(text_, p, cache, multistart_check=False)
        check(not ok_ and needle in out, f"fails: {what}")
        if ok_ or needle not in out:
            print(out)

    # one eigenvalue (a slow one, in a row whose eigenvalues are checked) by 1e-6 relative
    rows = [ln.split(",") for ln in lines]
    k_al = 3
    re_small = min(range(1, p.dim + 1), key=lambda j: abs(float(rows[k_al][col[f"re{j}"]])) + 1e300 *
                   (float(rows[k_al][col[f"re{j}"]]) == 0))
    v = float(rows[k_al][col[f"re{re_small}"]])
    expect_fail(edit(k_al, **{f"re{re_small}": repr(v * (1 + 1e-6))}),
                f"eigenvalue re{re_small} of row {k_al} times 1 + 1e-6", "EIG")
    kb = next(k for k, r in enumerate(rows) if r[0] == "balanced")
    j_b = next(j for j in range(1, p.dim + 1) if float(rows[kb][col[f"re{j}"]]) != 0)
    v = float(rows[kb][col[f"im{j_b}"]]) or float(rows[kb][col[f"re{j_b}"]])
    key = f"im{j_b}" if float(rows[kb][col[f"im{j_b}"]]) else f"re{j_b}"
    expect_fail(edit(kb, **{key: repr(v * (1 + 1e-6))}), f"balanced row: {key} times 1 + 1e-6", "EIG")
    expect_fail("\n".join(lines[:4] + lines[5:]) + "\n", "a dropped aligned row", "reference equilibria")
    expect_fail("\n".join([ln for ln in lines if not ln.startswith("balanced")]) + "\n",
                "all balanced rows dropped", "B is nonempty")
    spurious = rows[1][:]
    spurious[col["member"]] = "2"
    spurious[col["beta1"]] = spurious[col["beta2"]] = spurious[col["beta3"]] = repr(float(rows[1][col["beta1"]]) + 0.1)
    expect_fail(good + ",".join(spurious) + "\n", "a spurious aligned row (+++ member 2 again)", "reference equilibria")
    off = rows[kb][:]
    off[col["beta1"]] = repr(float(off[col["beta1"]]) + 1e-6)
    expect_fail(good + ",".join(off) + "\n", "a spurious balanced row 1e-6 rad off B", "not on B")
    expect_fail(edit(kb, n_structural_zero="0"), "n_structural_zero 0 on a balanced row", "n_structural_zero")
    st = rows[k_al][col["stable"]]
    expect_fail(edit(k_al, stable="0" if st == "1" else "1"), "a flipped 'stable'", "STABLE")
    m1, m2 = rows[1][col["member"]], rows[2][col["member"]]
    expect_fail(edit(1, member=m2) if m1 != m2 else good + "x", "a swapped member number", "member")
    # the count checks cover every row whatever --max-rows says
    expect_fail("\n".join(lines[:-2] + lines[-1:]) + "\n" + ",".join(spurious) + "\n",
                "a spurious row with --max-rows 1", "reference equilibria")
    ok, text = run_compare(good, p, cache, max_rows=1, multistart_check=False)
    check(ok and "eigenvalues of 1 checked" in text, "--max-rows 1 checks one row's eigenvalues")
    # bad input: wrong number of balls
    p4 = R.load_scene(scene("n4_unequal_stribeck"))
    try:
        run_compare(good, p4)
        check(False, "a 3-ball CSV against a 4-ball scene is bad input")
    except R.InputError:
        check(True, "a 3-ball CSV against a 4-ball scene is bad input (exit 2)")


def main():
    t0 = time.time()
    test_two_ball()
    test_loading()
    test_jacobian_trace_symmetry()
    test_counts()
    test_balanced()
    test_compare()
    print(f"{len(failures)} failure(s), {time.time() - t0:.1f} s")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
