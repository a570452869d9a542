#!/usr/bin/python3
"""Self-checks of mp_special.py (run: /usr/bin/python3 tests/reference/mp_special_selftest.py).

 1. first Lyapunov coefficient on systems with a known answer (with <q, q> = 1, l1 = 2a/w
    for the planar normal form a r^3; a centre-manifold coupling and quadratic terms
    (Guckenheimer-Holmes formula) must give the same);
 2. existence-function zeros: the together folds along omega of the default scene against
    the closed form (a quadratic in omega^2: U^2 (k - w^2 M)^2 = c^2 w^2 (D^2 - U^2));
 3. compare mode on hand-made special-points CSVs (default scene along omega): the exact
    values pass; a missing Hopf point, a Hopf point at a neutral saddle, a frequency or a
    parameter off by 1e-6 / 1e-7, a wrong label, family, count or l1 sign, an MX row and a
    non-converged row each fail. Takes ~1-2 min (one reference computation).
Exit status 0 if all pass.
"""
import io
import math
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import mp_special as S  # noqa: E402
import mp_reference as R  # noqa: E402
from mpmath import mp, mpf  # noqa: E402

SCENE = os.path.join(ROOT, "tests", "scenes", "continuation", "default_omega.toml")
failures = []


def check(ok, what):
    print(f"  {'ok  ' if ok else 'FAIL'} {what}")
    if not ok:
        failures.append(what)


def lyapunov_checks():
    print("check 1: first Lyapunov coefficient on known systems")
    with mp.workdps(60):
        for w in (mpf(1), mpf(2)):
            J = mp.matrix([[0, -w, 0], [w, 0, 0], [0, 0, -1]])
            x0 = [mpf(0)] * 3
            for a in (mpf(-1), mpf("0.3")):
                def planar(y, a=a, w=w):
                    r2 = y[0] ** 2 + y[1] ** 2
                    return [-w * y[1] + a * y[0] * r2, w * y[0] + a * y[1] * r2, -y[2]]

                def coupled(y, a=a, w=w):      # slow manifold y3 = a r^2 gives r' = a r^3
                    return [-w * y[1] + y[0] * y[2], w * y[0] + y[1] * y[2], -y[2] + a * (y[0] ** 2 + y[1] ** 2)]
                for f, name in ((planar, "planar"), (coupled, "centre manifold")):
                    l1 = S.first_lyapunov_generic(f, x0, J, w)
                    check(abs(l1 - 2 * a / w) < mpf(10) ** -30, f"{name} a={a} w={w}: l1 = {mp.nstr(l1, 12)}")
            # quadratic terms: f = x^2 + 2xy, g = y^2 - xy; GH: 16 a w = fxy(fxx+fyy) - gxy(gxx+gyy) - fxx gxx + fyy gyy
            J2 = mp.matrix([[0, -w], [w, 0]])

            def quad(y, w=w):
                return [-w * y[1] + y[0] ** 2 + 2 * y[0] * y[1], w * y[0] + y[1] ** 2 - y[0] * y[1]]
            a_gh = mpf(2 * 2 + 1 * 2) / (16 * w)
            l1 = S.first_lyapunov_generic(quad, [mpf(0)] * 2, J2, w)
            check(abs(l1 - 2 * a_gh / w) < mpf(10) ** -30, f"quadratic terms w={w}: l1 = {mp.nstr(l1, 12)}")


def fold_checks():
    print("check 2: together folds along omega against the closed form")
    p = R.load_scene(SCENE)
    par = S.Param(p, "omega")
    with mp.workdps(S.WORK_DPS):
        sps, _ = S.locate_boundaries(p, par, mpf(50), mpf(2000))
        got = sorted(sp.v for sp in sps if sp.label == "LP" and sp.family == "together")
        M, k, c, U = p.M(), mpf(p.k), mpf(p.c), mpf(p.U)
        D = p.ml(0) + p.ml(1)
        # U^2 M^2 x^2 - (2 U^2 k M + c^2 (D^2 - U^2)) x + U^2 k^2 = 0, x = w^2
        A, B, C = U * U * M * M, -(2 * U * U * k * M + c * c * (D * D - U * U)), U * U * k * k
        disc = mp.sqrt(B * B - 4 * A * C)
        want = sorted(mp.sqrt(x) for x in ((-B - disc) / (2 * A), (-B + disc) / (2 * A)))
        check(len(got) == 2, f"two together folds found ({len(got)})")
        for g, w in zip(got, want):
            check(abs(g - w) / w < mpf(10) ** -40, f"fold {mp.nstr(g, 20)} vs closed form, rel {mp.nstr(abs(g - w) / w, 2)}")


HEADER = ("branch,label,omega,q1,q2,beta1,beta2,q_abs,family,frequency,re,im,lyapunov,converged,"
          "n_unstable_before,n_unstable_after")


def row(br, lab, w, q1, q2, b1, b2, fam, f=None, l1=None, conv=1, nb=0, na=0):
    # None: an empty field, as the program writes where a value is not defined (frequency
    # and lyapunov off HB points; re, im, converged on MX rows).
    def cell(x):
        return "" if x is None else repr(x)
    return (f"{br},{lab},{w!r},{q1!r},{q2!r},{b1!r},{b2!r},{math.hypot(q1, q2)!r},{fam},{cell(f)},"
            f"{'' if conv is None else 0},{cell(f if f is not None else (None if conv is None else 0.0))},"
            f"{cell(l1)},{cell(conv)},{nb},{na}")


def compare_checks():
    print("check 3: compare mode on hand-made CSVs (one reference computation, ~1-2 min)")
    p = R.load_scene(SCENE)
    lo, hi = 49.986255669276645, 1999.4502267710657
    sps, notes, _ = S.special_points(p, "omega", lo, hi)
    ref = {sp.label + sp.family: sp for sp in sps if sp.label in S.LABELS}
    hb = next(sp for sp in sps if sp.label == "HB")
    lps = [sp for sp in sps if sp.label == "LP"]
    ns = next(sp for sp in sps if sp.label == "NS" and sp.family == "opposite")
    check(len(ref) == 2 and len(lps) == 2, "reference: 2 LP (together) and 1 HB (balanced)")

    def st(sp, swap=False):
        s = [float(x) for x in (sp.state[0], sp.state[1], R.wrap(sp.state[2]), R.wrap(sp.state[3]))]
        return s[:2] + s[2:][::-1] if swap else s
    w, f, l1 = float(hb.v), float(hb.freq), float(hb.lyap[0])
    base = [HEADER,
            row(0, "EP", lo, 0.0, 0.0, 2.1, 4.18, "balanced"),
            row(1, "HB", w, *st(hb), "balanced", f, l1, 1, 2, 0),
            row(2, "HB", w * (1 + 3e-12), *st(hb, swap=True), "balanced", f * (1 - 1e-11), l1, 1, 2, 0),
            row(3, "LP", float(lps[0].v), *st(lps[0]), "together", nb=0, na=1),
            row(4, "LP", float(lps[0].v) * (1 + 1e-12), *st(lps[0]), "together", nb=1, na=0),
            row(4, "LP", float(lps[1].v), *st(lps[1]), "together", nb=2, na=1),
            row(5, "EP", hi, 0.0, 0.0, 2.1, 4.18, "balanced")]
    variants = {
        "exact values": (base, True, "PASS found HB"),
        "missing Hopf point": ([r for r in base if ",HB," not in r], False, "FAIL missed HB"),
        "Hopf point at a neutral saddle": (base + [row(6, "HB", float(ns.v), *st(ns), "opposite", float(abs(ns.crit)),
                                                       1e-3, 1, 1, 1)], False, "neutral saddle"),
        "frequency off 1e-6": ([r.replace(repr(f), repr(f * (1 + 1e-6))) for r in base], False, "FREQUENCY"),
        "fold off 1e-7": ([r.replace(repr(float(lps[1].v)), repr(float(lps[1].v) * (1 + 1e-7))) for r in base], False,
                          "rel err 1.0e-07"),
        "fold labelled BP": ([r.replace(f",LP,{float(lps[1].v)!r}", f",BP,{float(lps[1].v)!r}") for r in base], False,
                             "reference says LP"),
        "Hopf point on the wrong family": ([r.replace(",balanced," + repr(f), ",together," + repr(f)) for r in base], False,
                                          "FAMILY together"),
        "wrong counts": ([r.replace(f",{l1!r},1,2,0", f",{l1!r},1,2,1") for r in base], False, "N_UNSTABLE"),
        "wrong l1 sign": ([r.replace(f",{l1!r},", f",{-l1!r},") for r in base], False, "LYAPUNOV SIGN"),
        "MX row": (base + [row(7, "MX", 300.0, 0.0, 0.0, 1.0, 1.0, "together", conv=None)], False, "MX (continuation failed)"),
        "not converged": (base[:4] + [row(3, "LP", float(lps[0].v), *st(lps[0]), "together", conv=0, nb=0, na=1)]
                          + base[5:], False, "NOT CONVERGED"),
    }
    with tempfile.TemporaryDirectory() as tmp:
        for name, (rows, want, why) in variants.items():
            path = os.path.join(tmp, "special_omega.csv")
            with open(path, "w") as fh:
                fh.write("# hand-made test file\n" + "\n".join(rows) + "\n")
            out = io.StringIO()
            got = S.compare(path, p, "omega", lo, hi, specials=sps, notes=notes, out=out)
            good = got == want and why in out.getvalue()
            check(good, f"{name}: {'PASS' if got else 'FAIL'} (expected {'PASS' if want else 'FAIL'}, "
                        f"report says {why!r}: {why in out.getvalue()})")
            if not good:
                print(out.getvalue())


def main():
    lyapunov_checks()
    fold_checks()
    compare_checks()
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
