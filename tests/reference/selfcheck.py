#!/usr/bin/python3
"""Self-checks of mp_reference.py (run: /usr/bin/python3 tests/reference/selfcheck.py).

 1. trace identity: sum(lambda) = trace J to 1e-40 relative (to sum |lambda|);
 2. conservative case (c = 0, law none): spectrum symmetric under lambda -> -lambda;
 3. massless-ball limit (m = 1e-9): rotor eigenvalues -> -zeta w_n +- i(w_d -+ w), ball
    eigenvalues -> roots of j l s^2 + gamma s +- w^2 |q| (model.md §7), to order 2ml/U;
 4. every equilibrium satisfies the full vector field to < 1e-50 (scaled per component),
    and the precision rerun (80 vs 120 digits) agrees to >= 50 digits;
 5. the hand-derived J equals central differences of the full vector field (mp.diff);
 6. stribeck at an equilibrium has the spectrum of coulomb with mu = mu_s;
 7. numpy.linalg.eigvals of the double-rounded J (default scene, kappa 1e3): the large
    eigenvalues agree to ~1e-13 (numpy only here, never in mp_reference.py).
Exit status 0 if all pass.
"""
import glob
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import mp_reference as R  # noqa: E402
from mpmath import mp, mpf, mpc  # noqa: E402

SCENES = os.path.join(ROOT, "tests", "scenes", "reference")
DEFAULT = os.path.join(ROOT, "data", "scenes", "default.toml")
failures = []


def check(ok, what):
    print(f"  {'ok  ' if ok else 'FAIL'} {what}")
    if not ok:
        failures.append(what)


def vf_scaled(p, e):
    """|f(x)| at the equilibrium, q accelerations over w^2 (Q + |q|), ball ones over w^2."""
    x = e.state + [mpf(0)] * 4
    f = R.vector_field(p, x)
    w2 = mpf(p.omega) ** 2
    qs = p.displacement_scale() + mp.hypot(e.q1, e.q2)
    return max(abs(f[4]) / (w2 * qs), abs(f[5]) / (w2 * qs), abs(f[6]) / w2, abs(f[7]) / w2,
               *(abs(v) for v in f[:4]))


def fd_jacobian_error(p, e):
    """max relative deviation of J from central differences of vector_field (column-scaled)."""
    J = e.J
    x0 = e.state + [mpf(0)] * 4
    Q = p.displacement_scale() + mp.hypot(e.q1, e.q2)
    w = mpf(p.omega)
    scales = [Q, Q, 1, 1, w * Q, w * Q, 1, 1]
    worst = mpf(0)
    for col in range(8):
        h = mpf(10) ** -25 * scales[col]
        xp = list(x0)
        xm = list(x0)
        xp[col] += h
        xm[col] -= h
        fp, fm = R.vector_field(p, xp), R.vector_field(p, xm)
        for row in range(8):
            d = (fp[row] - fm[row]) / (2 * h)
            rowscale = max(abs(J[row, k]) * scales[k] for k in range(8)) / scales[col]
            worst = max(worst, abs(d - J[row, col]) / rowscale)
    return worst


def main():
    scenes = sorted(glob.glob(os.path.join(SCENES, "*.toml"))) + [DEFAULT]
    print("checks 1, 4, 5 over all scenes")
    worst_tr = worst_vf = worst_fd = mpf(0)
    min_digits = 1e9
    for path in scenes:
        p = R.load_scene(path)
        eqs = R.verified(p)
        with mp.workdps(R.WORK_DPS):
            for e in eqs:
                worst_tr = max(worst_tr, e.trace_err)
                worst_vf = max(worst_vf, vf_scaled(p, e))
                min_digits = min(min_digits, e.digits)
                worst_fd = max(worst_fd, fd_jacobian_error(p, e))
    check(worst_tr < mpf(10) ** -40, f"trace identity, worst relative {mp.nstr(worst_tr, 3)}")
    check(worst_vf < mpf(10) ** -50, f"equilibria in the full vector field, worst scaled {mp.nstr(worst_vf, 3)}")
    check(min_digits >= 50, f"80 vs 120 digit reruns agree to >= {min_digits:.0f} digits")
    check(worst_fd < mpf(10) ** -30, f"J vs central differences of f, worst {mp.nstr(worst_fd, 3)}")

    print("check 2: conservative symmetry lambda -> -lambda")
    p = R.load_scene(os.path.join(SCENES, "conservative_none_c0.toml"))
    worst = mpf(0)
    for e in R.solve(p):
        sc = max(abs(z) for z in e.eig)
        for z in e.eig:
            worst = max(worst, min(abs(z + y) for y in e.eig) / max(abs(z), sc * mpf(10) ** -30))
    check(worst < mpf(10) ** -40, f"conservative spectrum symmetric, worst {mp.nstr(worst, 3)}")

    print("check 3: massless-ball limit (m = 1e-9)")
    p = R.load_scene(os.path.join(SCENES, "tiny_balls_m1e-9.toml"))
    order = 2 * p.balls[0].m * p.balls[0].l / p.U
    M, k, c, w = p.M(), mpf(p.k), mpf(p.c), mpf(p.omega)
    wn = mp.sqrt(k / M)
    z = c / (2 * M * wn)
    wd = wn * mp.sqrt(1 - z * z)
    rotor = [mpc(-z * wn, s * (wd + t * w)) for s in (1, -1) for t in (1, -1)]
    worst_r = worst_b = mpf(0)
    for e in R.solve(p):
        qn = mp.hypot(e.q1, e.q2)
        ball = []
        for i, b in enumerate((e.b1, e.b2)):
            bl = p.balls[i]
            gamma = -R.friction_slope0(p, i) / mpf(bl.m)
            side = 1 if mp.cos(b - mp.atan2(e.q2, e.q1)) > 0 else -1
            a2, a1, a0 = bl.j() * mpf(bl.l), gamma, side * w * w * qn
            sq = mp.sqrt(mpc(a1 * a1 - 4 * a2 * a0))
            ball += [(-a1 + sq) / (2 * a2), (-a1 - sq) / (2 * a2)]
        for ref, bucket in ((rotor, "r"), (ball, "b")):
            for x in ref:
                d = min(abs(y - x) for y in e.eig) / abs(x)
                if bucket == "r":
                    worst_r = max(worst_r, d)
                else:
                    worst_b = max(worst_b, d)
    check(worst_r < 10 * order, f"rotor eigenvalues vs closed form: worst rel {mp.nstr(worst_r, 3)} "
          f"(2ml/U = {order:.1e})")
    check(worst_b < 10 * order, f"ball eigenvalues vs j l s^2 + gamma s +- w^2|q|: worst rel {mp.nstr(worst_b, 3)}")

    print("check 6: stribeck spectrum = coulomb with mu = mu_s")
    ps = R.load_scene(os.path.join(SCENES, "stribeck_k1e4.toml"))
    pc = R.load_scene(os.path.join(SCENES, "stribeck_k1e4.toml"))
    pc.law = "coulomb"
    for b in pc.balls:
        b.mu = b.mu_s
    worst = mpf(0)
    for a, b in zip(R.solve(ps), R.solve(pc)):
        worst = max(worst, max(abs(x - y) / abs(y) for x, y in zip(a.eig, b.eig)))
    check(worst < mpf(10) ** -60, f"stribeck vs coulomb(mu_s), worst {mp.nstr(worst, 3)}")

    print("check 7: numpy eigvals of the double-rounded J (default scene, kappa 1e3)")
    try:
        import numpy as np
    except ImportError:
        print("  skip (no numpy)")
    else:
        p = R.load_scene(DEFAULT)
        for e in R.solve(p):
            Jd = np.array([[float(e.J[r, col]) for col in range(8)] for r in range(8)])
            ev = [mpc(complex(v)) for v in np.linalg.eigvals(Jd)]
            paired = R._pair_min(e.eig, ev)
            big = max(abs(x - y) / abs(x) for x, y in zip(e.eig, paired) if abs(x) > 1)
            small = [float(abs(x - y) / abs(x)) for x, y in zip(e.eig, paired) if abs(x) <= 1]
            check(big < 1e-12, f"{e.family:8s} |lambda| > 1: worst rel {mp.nstr(big, 3)}; "
                  f"small ones rel {', '.join(f'{s:.1e}' for s in small)} (dgeev, not checked)")
    print("ALL PASS" if not failures else f"{len(failures)} FAILED")
    return 1 if failures else 0


if __name__ == "__main__":
    with mp.workdps(R.WORK_DPS):
        sys.exit(main())
