#!/usr/bin/python3
"""High-precision (mpmath) reference for the special points along one-parameter families
of equilibria of the two-ball ABU model (docs/model.md §5-§6): folds (LP), branch points
(BP) and Hopf points (HB) in an interval of one parameter, and a comparer for the C++
program's special-points CSV.

No continuation is needed here: every equilibrium is a closed form of the parameters
(model.md §5), so a branch is a family member evaluated at each parameter value:

  balanced  member 1: b1 = +acos(x), member 2: b1 = -acos(x), x = (b^2 - a^2 - U^2)/(2aU)
  together  member 1: b = -phi + asin(x), member 2: b = pi - phi - asin(x),
            x = -C D/(U R), phi = atan2(C, K), R = hypot(K, C), D = a + b, b1 = b2 = b
  opposite  the same with D = a - b and b2 = b1 + pi
  (a = m1 l1, b = m2 l2, K = k - w^2 M, C = c w)

Each member is a continuous function of the parameter wherever it exists (C > 0 keeps
phi continuous), so the member numbers cannot swap inside an existence interval.

  LP  existence ends: g = U^2 R^2 - C^2 D^2 changes sign (|x| = 1, the two members merge).
  BP  balanced meets together where U^2 = (a + b)^2, opposite where U^2 = (a - b)^2.
      g and these are polynomials of degree <= 4 in every supported parameter, so their
      roots come from a polynomial fit and mp.polyroots (none can be missed), each then
      polished on the function itself; the LP is cross-checked by solving
      (family equation, det db/ds) = 0 with Newton from a perturbed start.
  HB  on each member: the characteristic polynomial P(l) = det(l^2 A - l G_v - G_s)
      (exact coefficients: Leibniz expansion over polynomial entries) and its Hurwitz
      determinant Delta_7 = a0^7 prod_{i<j} (l_i + l_j) (Orlando). Delta_7 is scanned on
      an adaptive grid, located by regula falsi (Illinois, bisection-safeguarded), and
      the root classified with mp.polyroots: a pair +-i w is a Hopf point; a real pair
      +-r (neutral saddle, NS) is not a special point and is only listed as such.

Precision: the scan runs at SCAN_DPS digits, every special point is located at WORK_DPS
and located again from scratch at VERIFY_DPS; the agreement is printed as digits.

    mp_special.py SCENE --param NAME --from A --to B [--set NAME=VALUE ...]
    mp_special.py --compare SPECIAL_CSV SCENE --param NAME --from A --to B [--set ...] [--rtol 1e-8]
"""
import argparse
import copy
import csv
import itertools
import math
import os
import sys
import time
import tomllib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mp_reference as R  # noqa: E402  (sets mp.dps = 80 on import; we use workdps blocks)
from mpmath import mp, mpf, mpc  # noqa: E402

SCAN_DPS = 40      # adaptive scan of Delta_7 (only signs and a closeness indicator needed)
WORK_DPS = 50      # location of every special point
VERIFY_DPS = 80    # independent second location; the agreement is reported
LYAP_DPS = 100     # first Lyapunov coefficient (finite differences of third order)

BASE_POINTS = 150          # base grid points per existence segment
CLUSTER_DECADES = 14       # geometric refinement down to 1e-14 relative at ends / resonance
MIN_WIDTH = 1e-14          # relative width below which the scan stops refining
NEAR = 0.1                 # indicator F below this: the interval gets a midpoint probe
MAX_SAMPLES = 20000        # per segment: a runaway refinement is reported, not hidden

FAMILIES = ("balanced", "together", "opposite")
LABELS = ("LP", "BP", "HB")


class InputError(R.InputError):
    pass


# ----------------------------------------------------------------------------------
# the parameter: p stays an R.Params; the continued value is stored as an mpf attribute
# (mp_reference converts every attribute with mpf(), so mpf values pass through exactly)
# ----------------------------------------------------------------------------------
class Param:
    def __init__(self, p, name):
        self.name = name
        if name in R.GLOBAL_SYMBOLS:
            self.targets = [(None, R.GLOBAL_SYMBOLS[name])]
        else:
            base, idx = name, None
            if name and name[-1].isdigit():
                base, idx = name[:-1], int(name[-1])
            if base not in R.BALL_SYMBOLS or (idx is not None and not 1 <= idx <= len(p.balls)):
                raise InputError(f"--param: unknown parameter {name!r}")
            self.targets = [(i, base) for i in range(len(p.balls)) if idx is None or idx == i + 1]

    def get(self, p):
        i, attr = self.targets[0]
        return getattr(p if i is None else p.balls[i], attr)

    def at(self, p, v):
        q = copy.copy(p)
        q.balls = [copy.copy(b) for b in p.balls]
        for i, attr in self.targets:
            setattr(q if i is None else q.balls[i], attr, mpf(v))
        return q


def balls_identical(p):
    """The two balls are interchangeable: swapping them maps equilibria to equilibria with
    the same spectrum (balanced member 1 <-> 2, opposite member 1 <-> 2)."""
    b1, b2 = p.balls
    keys = ("m", "l", "r", "rolling") + R.BALL_FRICTION_KEYS
    return all(getattr(b1, k) == getattr(b2, k) for k in keys)


# ----------------------------------------------------------------------------------
# family members (closed forms of model.md §5, written out so the member numbering is
# explicit and continuous in the parameter)
# ----------------------------------------------------------------------------------
def _D(p, family):
    return p.ml(0) + p.ml(1) if family == "together" else p.ml(0) - p.ml(1)


def member_state(p, family, member, clamp=False):
    """(q1, q2, b1, b2) of a family member, angles unwrapped; None where it does not
    exist. clamp: |x| slightly above 1 (a located fold or merge) is taken as 1."""
    U = mpf(p.U)
    a, b = p.ml(0), p.ml(1)
    if U == 0:
        return None                          # U = 0: sets, not isolated members
    if family == "balanced":
        x = (b * b - a * a - U * U) / (2 * a * U)
        if abs(x) > 1:
            if not clamp:
                return None
            x = mp.sign(x)
        th = mp.acos(x)
        b1 = th if member == 1 else -th
        z = -(a * mp.expj(b1) + U) / b
        return [mpf(0), mpf(0), b1, mp.atan2(z.imag, z.real)]
    K, C = p.KC()
    D = _D(p, family)
    Rr = mp.hypot(K, C)
    if Rr == 0:
        return None                          # K = C = 0: no bounded rotor state
    x = -C * D / (U * Rr)
    if abs(x) > 1:
        if not clamp:
            return None
        x = mp.sign(x)
    phi = mp.atan2(C, K)
    s = mp.asin(x)
    be = -phi + s if member == 1 else mp.pi - phi - s
    w = mpf(p.omega)
    qc = w * w * (U + D * mp.expj(be)) / mpc(K, C)
    return [qc.real, qc.imag, be, be + (0 if family == "together" else mp.pi)]


def existence_functions(p, par, family):
    """Functions of the parameter value whose sign changes end the family's existence
    (each >= 0 where it exists) and the special-point label of each zero."""
    def U2(q):
        return mpf(q.U) ** 2

    def g(fam):
        def f(v):
            q = par.at(p, v)
            K, C = q.KC()
            return U2(q) * (K * K + C * C) - (C * _D(q, fam)) ** 2
        return f
    if family in ("together", "opposite"):
        return [(g(family), "LP", family)]
    out = [(lambda v: (par.at(p, v).ml(0) + par.at(p, v).ml(1)) ** 2 - U2(par.at(p, v)), "BP", "together")]
    if not balls_identical(p):
        out.append((lambda v: U2(par.at(p, v)) - (par.at(p, v).ml(0) - par.at(p, v).ml(1)) ** 2, "BP", "opposite"))
    return out


# ----------------------------------------------------------------------------------
# polynomial zeros of the existence functions (all are polynomials of degree <= 4 in
# every supported parameter; the fit is checked, never assumed)
# ----------------------------------------------------------------------------------
def _cheb(n):
    return [mp.cos(mp.pi * (2 * k + 1) / (2 * n)) for k in range(n)]


def bracket_root(f, a, b, fa=None, fb=None, rel=None, maxit=400):
    """A zero of f in [a, b] (f(a) f(b) < 0): Illinois regula falsi with a bisection step
    whenever the bracket has not halved in three steps. Returns (root, bracket width)."""
    fa = f(a) if fa is None else fa
    fb = f(b) if fb is None else fb
    if fa == 0:
        return a, mpf(0)
    if fb == 0:
        return b, mpf(0)
    if mp.sign(fa) == mp.sign(fb):
        raise ValueError("no sign change in bracket")
    tol = (mpf(10) ** (-(mp.dps - 6)) if rel is None else mpf(rel)) * max(abs(a), abs(b))
    side, width0, stall = 0, abs(b - a), 0
    for _ in range(maxit):
        if abs(b - a) <= tol:
            break
        if stall >= 3:
            c = (a + b) / 2
            stall = 0
            width0 = abs(b - a) / 2
        else:
            c = (a * fb - b * fa) / (fb - fa)
            if not (min(a, b) < c < max(a, b)):
                c = (a + b) / 2
        fc = f(c)
        if fc == 0:
            return c, mpf(0)
        if mp.sign(fc) == mp.sign(fb):
            b, fb = c, fc
            if side == -1:
                fa /= 2
            side = -1
        else:
            a, fa = c, fc
            if side == 1:
                fb /= 2
            side = 1
        if abs(b - a) > width0 / 2:
            stall += 1
        else:
            stall, width0 = 0, abs(b - a)
    return (a + b) / 2, abs(b - a)


def poly_zeros(f, lo, hi, deg=8):
    """Zeros of f in the open interval (lo, hi) where f changes sign, plus touching zeros
    (even multiplicity) flagged. f must be a polynomial of degree <= deg in its argument:
    it is fitted on Chebyshev nodes and the fit checked at other points."""
    lo, hi = mpf(lo), mpf(hi)
    mid, half = (lo + hi) / 2, (hi - lo) / 2
    t = _cheb(deg + 1)
    vals = [f(mid + half * x) for x in t]
    scale = max(abs(v) for v in vals)
    if scale == 0:
        return [], []                         # identically zero: no isolated zeros
    V = mp.matrix([[x ** k for k in range(deg + 1)] for x in t])
    coef = mp.lu_solve(V, mp.matrix(vals))
    for x in (mpf(-1), mpf(1), mpf(1) / 3, -mpf(3) / 7):
        got = sum(coef[k] * x ** k for k in range(deg + 1))
        if abs(got - f(mid + half * x)) > mpf(10) ** (12 - mp.dps) * scale:
            raise InputError("existence function is not a low-degree polynomial in this parameter")
    c = [coef[k] for k in range(deg + 1)]
    cmax = max(abs(v) for v in c)
    while len(c) > 1 and abs(c[-1]) <= mpf(10) ** (15 - mp.dps) * cmax:
        c.pop()
    if len(c) <= 1:
        return [], []
    roots = mp.polyroots(c[::-1], maxsteps=400, extraprec=4 * mp.prec)
    crossing, touching = [], []
    for z in roots:
        z = mpc(z)
        if abs(z.imag) > mpf(10) ** (-mp.dps // 3) or not (-1 < z.real < 1):
            continue
        v = mid + half * z.real
        # polish on f itself inside a small bracket; no sign change there: even multiplicity
        d = half * mpf(10) ** (-mp.dps // 3)
        a, b = max(lo, v - d), min(hi, v + d)
        fa, fb = f(a), f(b)
        if fa != 0 and fb != 0 and mp.sign(fa) != mp.sign(fb):
            r, _ = bracket_root(f, a, b, fa, fb)
            if not any(abs(r - s) <= mpf(10) ** (10 - mp.dps) * abs(r) for s in crossing):
                crossing.append(r)
        else:
            touching.append(v)
    return sorted(crossing), sorted(touching)


# ----------------------------------------------------------------------------------
# characteristic polynomial and Hurwitz determinant
# ----------------------------------------------------------------------------------
_PERMS = [(perm, (-1) ** sum(1 for i in range(4) for j in range(i + 1, 4) if perm[i] > perm[j]))
          for perm in itertools.permutations(range(4))]


def _pmul(a, b):
    out = [mpf(0)] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        if x:
            for j, y in enumerate(b):
                out[i + j] += x * y
    return out


def charpoly(p, state):
    """Coefficients a0..a8 (descending) of P(l) = det(l^2 A - l G_v - G_s): the Leibniz
    expansion of the 4x4 determinant over quadratic polynomial entries, exact up to the
    rounding of the working precision (no interpolation). a0 = det A > 0."""
    Gs, Gv = R.db_ds_dsdot(p, state)
    A = R.mass_matrix(p, state[2], state[3])
    E = [[[-Gs[i, j], -Gv[i, j], A[i, j]] for j in range(4)] for i in range(4)]
    c = [mpf(0)] * 9
    for perm, sg in _PERMS:
        t = E[0][perm[0]]
        for i in range(1, 4):
            t = _pmul(t, E[i][perm[i]])
        for k in range(9):
            c[k] += sg * t[k]
    return c[::-1]


def hurwitz(a, order=7):
    """Leading principal minor Delta_order of the Hurwitz matrix of a0 l^n + ... + an."""
    n = len(a) - 1
    H = mp.zeros(order, order)
    for i in range(order):
        for j in range(order):
            k = 2 * (j + 1) - (i + 1)
            if 0 <= k <= n:
                H[i, j] = a[k]
    return mp.det(H)


def clean_roots(roots):
    """Imaginary parts below rounding level (10^(10 - dps) |z|) set to 0: P is real."""
    out = []
    for z in roots:
        z = mpc(z)
        if abs(z.imag) <= mpf(10) ** (10 - mp.dps) * abs(z):
            z = mpc(z.real, 0)
        out.append(z)
    return out


def eigenvalues(a):
    """All roots of P (the 8 eigenvalues of J) with mp.polyroots."""
    return clean_roots(mp.polyroots(a, maxsteps=800, extraprec=3 * mp.prec))


def aberth(a, guess, maxit=60):
    """Roots of P by the Aberth-Ehrlich iteration started from `guess` (the neighbouring
    sample's roots, slightly rotated so a real pair can split into a complex one). Only
    for the scan indicator; None if it does not converge (then mp.polyroots is used)."""
    n = len(a) - 1
    z = [mpc(g) * mpc(1, mpf(10) ** -4) + mpf(10) ** -30 for g in guess]
    tol = mpf(10) ** (8 - mp.dps)
    for _ in range(maxit):
        worst = mpf(0)
        for k in range(n):
            zk = z[k]
            pv, dv = mpc(a[0]), mpc(0)
            for c in a[1:]:
                dv = dv * zk + pv
                pv = pv * zk + c
            if pv == 0:
                continue
            ratio = pv / dv
            s = sum(1 / (zk - z[j]) for j in range(n) if j != k)
            w = ratio / (1 - ratio * s)
            z[k] = zk - w
            worst = max(worst, abs(w) / abs(z[k]))
        if worst < tol:
            return clean_roots(z)
    return None


def pair_closeness(lam):
    """Orlando: Delta_7 ~ prod_{i<j} (l_i + l_j). Returns (F, sign) with F the smallest
    |l_i + l_j| / (|l_i| + |l_j|) (how close Delta_7 is to a zero, scale-free) and the
    sign of the product (must equal the sign of the Hurwitz determinant)."""
    F, sign = mpf(2), 1
    for i, j in itertools.combinations(range(len(lam)), 2):
        s = lam[i] + lam[j]
        den = abs(lam[i]) + abs(lam[j])
        F = min(F, abs(s) / den if den else mpf(0))
        if abs(s.imag) <= mpf(10) ** (10 - mp.dps) * den:      # real factor (or conjugate pair)
            if s.real < 0:
                sign = -sign
    return F, sign


def n_unstable(lam):
    return sum(1 for z in lam if z.real > 0)


# ----------------------------------------------------------------------------------
# a branch = (family, member) evaluated along the parameter
# ----------------------------------------------------------------------------------
class Member:
    def __init__(self, p, par, family, member):
        self.p, self.par, self.family, self.member = p, par, family, member

    def name(self):
        return f"{self.family}/{self.member}"

    def state(self, v, clamp=False):
        return member_state(self.par.at(self.p, v), self.family, self.member, clamp)

    def poly(self, v, state=None):
        q = self.par.at(self.p, v)
        s = member_state(q, self.family, self.member, clamp=True) if state is None else state
        return charpoly(q, s)

    def delta7(self, v):
        return hurwitz(self.poly(v))

    def spectrum(self, v):
        return eigenvalues(self.poly(v))


class Sample:
    __slots__ = ("v", "sign", "lam", "F", "nu", "orlando_ok")


def _sample(mb, v, guess):
    s = Sample()
    s.v = v
    a = mb.poly(v)
    d7 = hurwitz(a)
    s.sign = int(mp.sign(d7))
    lam = aberth(a, guess) if guess is not None else None
    if lam is None:
        lam = eigenvalues(a)
    s.lam = lam
    s.F, osign = pair_closeness(lam)
    s.nu = n_unstable(lam)
    # Hurwitz sign vs Orlando sign: equal unless Delta_7 is within rounding of zero
    s.orlando_ok = (osign == s.sign) or s.F < mpf(10) ** (15 - mp.dps)
    return s


def _midpoint(a, b):
    return mp.sqrt(a * b) if a > 0 and b > 0 and b / a > 4 else (a + b) / 2


def scan_segment(mb, lo, hi, inner_points=(), stats=None):
    """Adaptive scan of Delta_7 along a member on [lo, hi] (where it exists). Returns the
    samples (sorted) and the brackets [(Sa, Sb)] where Delta_7 changes sign."""
    lo, hi = mpf(lo), mpf(hi)
    n = BASE_POINTS
    if lo > 0 and hi / lo > 2:
        pts = [lo * (hi / lo) ** (mpf(k) / n) for k in range(n + 1)]
    else:
        pts = [lo + (hi - lo) * k / n for k in range(n + 1)]
    # geometric clusters toward the ends (folds, merges: the state goes like a square
    # root there) and around resonance points inside (K = 0: fast spectral changes)
    for c, both in [(lo, False), (hi, False)] + [(c, True) for c in inner_points]:
        for k in range(2, 2 * CLUSTER_DECADES + 1):
            d = abs(c) * mpf(10) ** (-mpf(k) / 2)
            for v in ((c + d, c - d) if both else ((c + d,) if c == lo else (c - d,))):
                if lo < v < hi:
                    pts.append(v)
        if both and lo < c < hi:
            pts.append(c)
    # shrink the end points a hair inward: at an exact fold / merge the member is degenerate
    eps = mpf(10) ** (-2 * CLUSTER_DECADES)
    pts = sorted(set(pts))
    pts[0] = lo + (hi - lo) * eps if lo != 0 else lo
    pts[-1] = hi - (hi - lo) * eps
    samples = []
    guess = None
    for v in pts:
        s = _sample(mb, v, guess)
        guess = s.lam
        samples.append(s)
    # adaptive refinement: every interval where Delta_7 may be near a zero gets midpoint
    # probes until it is flat (no dip of F below half the end average), without sign or
    # count change, or narrower than MIN_WIDTH.
    work = list(zip(samples[:-1], samples[1:]))
    final = []
    count = len(samples)
    runaway = False
    while work:
        sa, sb = work.pop()
        width_ok = abs(sb.v - sa.v) > MIN_WIDTH * max(abs(sa.v), abs(sb.v))
        event = sa.sign != sb.sign or sa.nu != sb.nu
        if not width_ok or (not event and min(sa.F, sb.F) >= NEAR):
            final.append((sa, sb))
            continue
        if count >= MAX_SAMPLES:
            runaway = True
            final.append((sa, sb))
            continue
        m = _midpoint(sa.v, sb.v)
        sm = _sample(mb, m, sa.lam)
        count += 1
        dip = sm.F < (sa.F + sb.F) / 4
        ev2 = sa.sign != sm.sign or sm.sign != sb.sign or sa.nu != sm.nu or sm.nu != sb.nu
        if ev2 or dip:
            work.append((sa, sm))
            work.append((sm, sb))
        else:
            final.append((sa, sm))
            final.append((sm, sb))
    final.sort(key=lambda t: t[0].v)
    allsamples = [final[0][0]] + [t[1] for t in final]
    brackets = [(sa, sb) for sa, sb in final if sa.sign != sb.sign]
    if stats is not None:
        stats["samples"] = stats.get("samples", 0) + len(allsamples)
        stats["runaway"] = stats.get("runaway", False) or runaway
        stats["orlando_mismatch"] = stats.get("orlando_mismatch", 0) + sum(1 for s in allsamples if not s.orlando_ok)
    return allsamples, brackets


# ----------------------------------------------------------------------------------
# special points
# ----------------------------------------------------------------------------------
class Special:
    def __init__(self, label, v, family, members, state):
        self.label = label              # LP, BP, HB, NS (neutral saddle: not special)
        self.v = v                      # parameter value (VERIFY_DPS result)
        self.family = family            # family of the first incidence
        self.incidences = []            # (family, member, (n_before, n_after) or (n1, n2))
        self.members = members
        self.state = state              # (q1, q2, b1, b2) unwrapped
        self.freq = None                # HB: w_H
        self.crit = None                # critical eigenvalue
        self.digits = None              # agreement WORK_DPS vs VERIFY_DPS location
        self.lyap = None                # HB: (l1, digits)
        self.check = ""                 # cross-check text
        self.notes = []

    def n_pairs(self, family=None):
        return [nn for fam, mem, nn in self.incidences if family is None or fam == family]


def _spectrum_at(p, par, family, member, v):
    q = par.at(p, v)
    s = member_state(q, family, member)
    if s is None:
        return None
    return eigenvalues(charpoly(q, s))


def _side_delta(v, neighbours, lo, hi):
    """Relative offset for 'before / after' counts: 1e-6, but well inside the distance
    to the nearest other special point or end of the interval."""
    d = mpf(10) ** -6 * abs(v)
    for w in list(neighbours) + [lo, hi]:
        if w != v and abs(w - v) > 0:
            d = min(d, abs(w - v) / 4)
    return d


def det_scaled(Gs):
    """det(db/ds) over the product of its row norms: 0 at a fold or branch point, O(1)
    far from one."""
    den = mpf(1)
    for i in range(4):
        den *= mp.sqrt(sum(Gs[i, j] ** 2 for j in range(4)))
    return mp.det(Gs) / den


def _fold_crosscheck(p, par, family, v_f, state):
    """Newton on (E(b, v), det db/ds (s(b, v), v)) = 0 with E the family equation
    K U sin b + C U cos b + C D = 0 and s(b, v) = (q from the rotor equations, b, b + off),
    started 1e-4 off the closed-form fold. Returns the relative difference in v."""
    off = 0 if family == "together" else mp.pi

    def F(u, bb):
        v = v_f * (1 + u)
        q = par.at(p, v)
        K, C = q.KC()
        U, D, w = mpf(q.U), _D(q, family), mpf(q.omega)
        qc = w * w * (U + D * mp.expj(bb)) / mpc(K, C)
        Gs, _ = R.db_ds_dsdot(q, [qc.real, qc.imag, bb, bb + off])
        E = (K * U * mp.sin(bb) + C * U * mp.cos(bb) + C * D) / (mp.hypot(K, C) * U + abs(C * D))
        return [E, det_scaled(Gs)]
    x = [mpf(10) ** -4, state[2] + mpf(10) ** -3]
    h = mpf(10) ** (-mp.dps // 2)
    for _ in range(100):
        f0 = F(*x)
        J = mp.matrix(2, 2)
        for k in range(2):
            xp = list(x)
            xp[k] += h
            fk = F(*xp)
            for r in range(2):
                J[r, k] = (fk[r] - f0[r]) / h
        dx = mp.lu_solve(J, -mp.matrix(f0))
        x = [x[0] + dx[0], x[1] + dx[1]]
        if abs(dx[0]) < mpf(10) ** (-mp.dps // 2 + 4) and abs(dx[1]) < mpf(10) ** (-mp.dps // 2 + 4):
            break
    return abs(x[0])


def locate_boundaries(p, par, lo, hi):
    """LP and BP points in (lo, hi): zeros of the existence functions. Returns the list of
    Special (without counts) and the touching zeros (notes)."""
    out, notes = [], []
    done = set()
    for family in FAMILIES:
        for f, label, other in existence_functions(p, par, family):
            key = (label, min(family, other), max(family, other))
            if key in done:
                continue
            done.add(key)
            cross, touch = poly_zeros(f, lo, hi)
            for v in touch:
                notes.append(f"{label} {family}/{other}: the existence function touches 0 at "
                             f"{mp.nstr(v, 17)} without a sign change (degenerate, not reported)")
            for v in cross:
                if label == "LP":
                    sp = Special("LP", v, family, (1, 2), member_state(par.at(p, v), family, 1, clamp=True))
                else:
                    sp = Special("BP", v, "balanced", (1, 2), member_state(par.at(p, v), "balanced", 1, clamp=True))
                    sp.other = other
                out.append(sp)
    return out, notes


def _polish_boundary(p, par, sp, lo, hi):
    """Recompute the zero at VERIFY_DPS from a bracket around the WORK_DPS value."""
    fams = {"LP": sp.family, "BP": "balanced"}[sp.label]
    funcs = [f for f, lab, oth in existence_functions(p, par, fams)
             if lab == sp.label and (sp.label == "LP" or oth == sp.other)]
    f = funcs[0]
    v0 = +sp.v
    with mp.workdps(VERIFY_DPS):
        d = abs(v0) * mpf(10) ** (-WORK_DPS + 10)
        a, b = v0 - d, v0 + d
        if mp.sign(f(a)) == mp.sign(f(b)):
            a, b = max(mpf(lo), v0 * (1 - mpf(10) ** -8)), min(mpf(hi), v0 * (1 + mpf(10) ** -8))
        v1, _ = bracket_root(f, a, b)
        sp.digits = float(-mp.log10(abs(v1 - v0) / abs(v1))) if v1 != v0 else float(WORK_DPS)
        sp.v = v1
        fam = sp.family
        sp.state = member_state(par.at(p, v1), fam, 1, clamp=True)


def boundary_counts(p, par, sp, neighbours, lo, hi):
    """n_unstable of the incident branches next to an LP / BP (at WORK_DPS)."""
    v = sp.v
    d = _side_delta(v, neighbours, lo, hi)
    # a neighbour closer than 1e-8 relative: keep the same number of digits inside the gap
    with mp.workdps(mp.dps + max(0, int(mp.ceil(-mp.log10(d / abs(v)))) - 8)):
        _boundary_counts(p, par, sp, v, d)


def _boundary_counts(p, par, sp, v, d):
    if sp.label == "LP":
        # the two merging members, on the side where they exist
        for side in (-1, 1):
            lam1 = _spectrum_at(p, par, sp.family, 1, v + side * d)
            if lam1 is not None:
                lam2 = _spectrum_at(p, par, sp.family, 2, v + side * d)
                sp.incidences.append((sp.family, (1, 2), (n_unstable(lam1), n_unstable(lam2))))
                sp.exists_side = side
                break
        q = par.at(p, v)
        Gs, _ = R.db_ds_dsdot(q, member_state(q, sp.family, 1, clamp=True))
        dv = _fold_crosscheck(p, par, sp.family, v, sp.state)
        sp.check = (f"det(db/ds) scaled {mp.nstr(det_scaled(Gs), 2)}; (E, det db/ds) = 0 Newton "
                    f"from 1e-4 off gives the same p to {mp.nstr(dv, 2)} rel")
        return
    # BP: balanced members (existing side) and the member of the other family through it
    for side in (-1, 1):
        lam1 = _spectrum_at(p, par, "balanced", 1, v + side * d)
        if lam1 is not None:
            lam2 = _spectrum_at(p, par, "balanced", 2, v + side * d)
            sp.incidences.append(("balanced", (1, 2), (n_unstable(lam1), n_unstable(lam2))))
            break
    q = par.at(p, v)
    best = None
    for mem in (1, 2):
        s = member_state(q, sp.other, mem, clamp=True)
        if s is not None and (best is None or mp.hypot(s[0], s[1]) < best[0]):
            best = (mp.hypot(s[0], s[1]), mem, s)
    if best is not None:
        mem = best[1]
        before = _spectrum_at(p, par, sp.other, mem, v - d)
        after = _spectrum_at(p, par, sp.other, mem, v + d)
        sp.incidences.append((sp.other, (mem,), (None if before is None else n_unstable(before),
                                                  None if after is None else n_unstable(after))))
        sp.through = (sp.other, mem)
        Gs, _ = R.db_ds_dsdot(q, best[2])
        sp.check = (f"|q| of {sp.other}/{mem} there {mp.nstr(best[0], 2)} m; det(db/ds) scaled "
                    f"{mp.nstr(det_scaled(Gs), 2)}")


def locate_hopf(mb, sa, sb, dps):
    """Zero of Delta_7 in the bracket (sa.v, sb.v) at dps digits."""
    with mp.workdps(dps):
        f = mb.delta7
        a, b = mpf(sa.v), mpf(sb.v)
        fa, fb = f(a), f(b)
        if mp.sign(fa) == mp.sign(fb):
            return None
        v, _ = bracket_root(f, a, b, fa, fb)
        return v


def classify_zero(mb, v):
    """At a zero of Delta_7: the pair (l_i, l_j) with l_i + l_j = 0. A conjugate pair
    +-i w (w > 0 clearly) is a Hopf point; a real pair +-r a neutral saddle."""
    a = mb.poly(v)
    lam = eigenvalues(a)
    best = None
    for i, j in itertools.combinations(range(8), 2):
        r = abs(lam[i] + lam[j]) / (abs(lam[i]) + abs(lam[j]))
        if best is None or r < best[0]:
            best = (r, i, j)
    r, i, j = best
    z1, z2 = lam[i], lam[j]
    w = max(abs(z1.imag), abs(z2.imag))
    scale = abs(z1)
    if w > mpf(10) ** (-mp.dps // 2) * scale and abs(z1 - mp.conj(z2)) <= mpf(10) ** (-mp.dps // 2) * scale:
        kind = "HB"
        crit = z1 if z1.imag > 0 else z2
    elif z1.imag == 0 and z2.imag == 0:
        kind = "NS"
        crit = z1 if z1.real > 0 else z2
    else:
        kind = "??"
        crit = z1
    return kind, crit, r, lam


# ----------------------------------------------------------------------------------
# first Lyapunov coefficient (Kuznetsov, Elements of applied bifurcation theory, eq. 3.20)
# ----------------------------------------------------------------------------------
def first_lyapunov_generic(f, x0, J, w, h=None):
    """l1 = 1/(2w) Re[<p, C(q,q,qb)> - 2 <p, B(q, J^-1 B(q,qb))> + <p, B(qb, (2iw - J)^-1 B(q,q))>]
    with J q = i w q, J^T p = -i w p, <q, q> = 1, <p, q> = 1 (<u, v> = conj(u)^T v).
    B and C are the second and third derivatives of f at x0, by central differences of
    step h at the current (high) precision, extended complex-multilinearly from real
    directions (each scaled to unit max-norm first)."""
    n = len(x0)
    h = mpf(10) ** (-mp.dps // 5) if h is None else h
    iw = mpc(0, w)

    def null(Mx):
        # inverse iteration with a tiny shift (Mx can be exactly singular); three steps
        # leave an error (shift / gap)^3, far below the working precision
        Ms = Mx + mpc(1, 1) * mpf(10) ** (-mp.dps // 3) * mp.mnorm(Mx, 1) * mp.eye(n)
        v = mp.matrix([mpc(1, k + 1) / (k + 2) for k in range(n)])
        for _ in range(3):
            v = mp.lu_solve(Ms, v)
            v = v / mp.norm(v)
        return v
    I = mp.eye(n)
    q = null(J - iw * I)
    pv = null(J.T + iw * I)
    q = q / mp.sqrt(sum(abs(q[k]) ** 2 for k in range(n)))
    c = sum(mp.conj(pv[k]) * q[k] for k in range(n))
    pv = pv / mp.conj(c)

    def fx(d):
        return mp.matrix(f([x0[k] + d[k] for k in range(n)]))

    def B_real(u, v):
        su, sv = max(abs(x) for x in u), max(abs(x) for x in v)
        if su == 0 or sv == 0:
            return mp.matrix(n, 1)
        u = [x / su for x in u]
        v = [x / sv for x in v]
        acc = mp.matrix(n, 1)
        for s1, s2 in itertools.product((1, -1), repeat=2):
            acc += s1 * s2 * fx([h * (s1 * u[k] + s2 * v[k]) for k in range(n)])
        return acc * (su * sv / (4 * h * h))

    def C_real(u, v, t):
        su, sv, st = (max(abs(x) for x in y) for y in (u, v, t))
        if su == 0 or sv == 0 or st == 0:
            return mp.matrix(n, 1)
        u, v, t = [x / su for x in u], [x / sv for x in v], [x / st for x in t]
        acc = mp.matrix(n, 1)
        for s1, s2, s3 in itertools.product((1, -1), repeat=3):
            acc += s1 * s2 * s3 * fx([h * (s1 * u[k] + s2 * v[k] + s3 * t[k]) for k in range(n)])
        return acc * (su * sv * st / (8 * h ** 3))

    def parts(z):
        return [[mpc(z[k]).real for k in range(n)], [mpc(z[k]).imag for k in range(n)]]

    def B(u, v):
        (ur, ui), (vr, vi) = parts(u), parts(v)
        out = mp.matrix(n, 1)
        for (a, ca), (b, cb) in itertools.product(((ur, 1), (ui, 1j)), ((vr, 1), (vi, 1j))):
            out += B_real(a, b) * (ca * cb)
        return out

    def Cf(u, v, t):
        out = mp.matrix(n, 1)
        for (a, ca), (b, cb), (d, cd) in itertools.product(*[((x[0], 1), (x[1], 1j)) for x in (parts(u), parts(v), parts(t))]):
            out += C_real(a, b, d) * (ca * cb * cd)
        return out

    def dot(u, v):
        return sum(mp.conj(u[k]) * v[k] for k in range(n))
    qb = mp.matrix([mp.conj(q[k]) for k in range(n)])
    Bqqb = B(q, qb)
    Bqq = B(q, q)
    t1 = dot(pv, Cf(q, q, qb))
    t2 = dot(pv, B(q, mp.lu_solve(J, Bqqb)))
    t3 = dot(pv, B(qb, mp.lu_solve(2 * iw * I - J, Bqq)))
    return (t1 - 2 * t2 + t3).real / (2 * w)


def first_lyapunov(p, state, w):
    """l1 of the model at a Hopf point, in SI state coordinates with <q, q> = 1 (the
    normalization the C++ program uses; the sign does not depend on it). Computed at
    LYAP_DPS with two step sizes; returns (l1, digits of agreement)."""
    vals = []
    with mp.workdps(LYAP_DPS):
        x0 = [mpf(v) for v in state] + [mpf(0)] * 4
        J = R.jacobian(p, x0)
        for h in (mpf(10) ** -20, mpf(10) ** -17):
            vals.append(first_lyapunov_generic(lambda x: R.vector_field(p, x), x0, J, mpf(w), h))
        d = abs(vals[0] - vals[1]) / abs(vals[0]) if vals[0] else mpf(1)
    return vals[0], (float(-mp.log10(d)) if d > 0 else float(LYAP_DPS))


# ----------------------------------------------------------------------------------
# the whole computation
# ----------------------------------------------------------------------------------
def _state_key(state):
    return [R.wrap(state[2]), R.wrap(state[3])]


def same_point(p, s1, s2, tol):
    """States equal within tol (q relative to the displacement scale, angles mod 2 pi),
    or equal after swapping the balls when they are identical."""
    Q = p.displacement_scale()

    def dist(a, b):
        dq = mp.hypot(a[0] - b[0], a[1] - b[1]) / (Q + mp.hypot(b[0], b[1]))
        return max(dq, R._angdist(a[2], b[2]), R._angdist(a[3], b[3]))
    d = dist(s1, s2)
    if balls_identical(p):
        d = min(d, dist(s1, [s2[0], s2[1], s2[3], s2[2]]))
    return d <= tol, d


def special_points(p, name, lo, hi, lyapunov=True, log=None):
    """Every LP, BP, HB (and, for information, NS) in the open interval (lo, hi) of the
    parameter `name`. Returns (specials sorted by parameter, notes, stats)."""
    par = Param(p, name)
    lo, hi = float(lo), float(hi)
    if not lo < hi:
        raise InputError("--from must be below --to")
    stats, notes = {}, []
    identical = balls_identical(p)
    with mp.workdps(WORK_DPS):
        LO, HI = mpf(lo), mpf(hi)
        bounds, bnotes = locate_boundaries(p, par, LO, HI)
        notes += bnotes
        # K = 0 (resonance) inside: cluster scan points there; K = C = 0: no rotor state
        res_cross, res_touch = poly_zeros(lambda v: par.at(p, v).KC()[0], LO, HI)
        resonance = res_cross + res_touch
        singular = [v for v in resonance if par.at(p, v).KC()[1] == 0]
        for v in singular:
            notes.append(f"K = C = 0 at {mp.nstr(v, 17)}: together/opposite families undefined there")
    for sp in bounds:
        _polish_boundary(p, par, sp, lo, hi)
    specials = list(bounds)
    # members to scan (a swap image of a scanned member has the same spectrum)
    members = [("balanced", 1), ("together", 1), ("together", 2), ("opposite", 1)]
    if not identical:
        members += [("balanced", 2), ("opposite", 2)]
    mirror = {("balanced", 1): ("balanced", 2), ("opposite", 1): ("opposite", 2)} if identical else {}
    hopfs = []
    with mp.workdps(WORK_DPS):
        for family, member in members:
            mb = Member(p, par, family, member)
            # the member's own existence ends, and branch points it passes (a real eigenvalue
            # crosses 0 there, which Delta_7 does not see)
            own = [sp.v for sp in bounds if (sp.label == "LP" and sp.family == family)
                   or (sp.label == "BP" and family in ("balanced", sp.other))]
            cuts = sorted(set([LO, HI] + [v for v in own if LO < v < HI] + singular))
            for a, b in zip(cuts[:-1], cuts[1:]):
                m = (a + b) / 2
                if mb.state(m) is None:
                    continue
                t0 = time.time()
                # a segment narrower than 1e-8 relative (e.g. between a fold and a branch point
                # that nearly coincide) loses digits of parameter resolution: add them back
                lost = max(0, int(mp.ceil(-mp.log10((b - a) / max(abs(a), abs(b))))) - 8)
                with mp.workdps(SCAN_DPS + lost):
                    samples, brackets = scan_segment(mb, a, b, [v for v in resonance if a < v < b], stats)
                if log:
                    log(f"# scanned {mb.name()} on [{mp.nstr(a, 8)}, {mp.nstr(b, 8)}]: {len(samples)} samples, "
                        f"{len(brackets)} sign changes of Delta_7, {time.time() - t0:.1f} s")
                # every change of n_unstable inside the segment must sit in a Delta_7 bracket
                for sa, sb in zip(samples[:-1], samples[1:]):
                    if sa.nu != sb.nu and sa.sign == sb.sign:
                        notes.append(f"WARNING {mb.name()}: n_unstable {sa.nu} -> {sb.nu} between "
                                     f"{mp.nstr(sa.v, 17)} and {mp.nstr(sb.v, 17)} without a Delta_7 "
                                     "sign change (unresolved)")
                for sa, sb in brackets:
                    v = locate_hopf(mb, sa, sb, WORK_DPS + lost)
                    if v is None:
                        notes.append(f"WARNING {mb.name()}: Delta_7 sign change at scan precision between "
                                     f"{mp.nstr(sa.v, 17)} and {mp.nstr(sb.v, 17)} not confirmed at "
                                     f"{WORK_DPS + lost} digits")
                        continue
                    with mp.workdps(WORK_DPS + lost):
                        kind, crit, r, lam = classify_zero(mb, v)
                    # second, independent location at VERIFY_DPS from the scan bracket
                    v2 = locate_hopf(mb, sa, sb, VERIFY_DPS + lost)
                    with mp.workdps(VERIFY_DPS + lost):
                        kind2, crit2, r2, _ = classify_zero(mb, v2)
                        dig = float(-mp.log10(abs(v2 - v) / abs(v2))) if v2 != v else float(WORK_DPS)
                        st = mb.state(v2, clamp=True)
                    sp = Special(kind, v2, family, (member,), st)
                    sp.dps = WORK_DPS + lost
                    sp.crit, sp.digits = crit2, dig
                    sp.freq = abs(crit2.imag) if kind2 == "HB" else None
                    sp.check = f"|l_i + l_j|/(|l_i| + |l_j|) = {mp.nstr(r2, 2)} at {VERIFY_DPS} digits"
                    if kind != kind2:
                        sp.notes.append(f"classified {kind} at {WORK_DPS} digits, {kind2} at {VERIFY_DPS}")
                    sp.members = (member,) + ((mirror[(family, member)][1],) if (family, member) in mirror else ())
                    sp.segment = (a, b)
                    sp.notes.append(f"on the {family}/{member} segment [{mp.nstr(a, 12)}, {mp.nstr(b, 12)}]")
                    hopfs.append(sp)
    specials += hopfs
    # counts before / after for the Delta_7 zeros along increasing parameter
    with mp.workdps(WORK_DPS):
        allv = [sp.v for sp in specials]
        for sp in hopfs:
            a, b = sp.segment
            with mp.workdps(sp.dps):
                d = _side_delta(sp.v, allv, a, b)
                lb = _spectrum_at(p, par, sp.family, sp.members[0], sp.v - d)
                la = _spectrum_at(p, par, sp.family, sp.members[0], sp.v + d)
            sp.incidences.append((sp.family, sp.members, (n_unstable(lb), n_unstable(la))))
        for sp in bounds:
            boundary_counts(p, par, sp, allv, lo, hi)
    if lyapunov:
        for sp in hopfs:
            if sp.label == "HB":
                q = par.at(p, sp.v)
                sp.lyap = first_lyapunov(q, sp.state, sp.freq)
    specials.sort(key=lambda s: s.v)
    return specials, notes, stats


# ----------------------------------------------------------------------------------
# printing
# ----------------------------------------------------------------------------------
def _fmt_state(s):
    return (f"q1={mp.nstr(s[0], 12)} q2={mp.nstr(s[1], 12)} "
            f"beta1={mp.nstr(R.wrap(s[2]), 12)} beta2={mp.nstr(R.wrap(s[3]), 12)}")


def _fmt_inc(sp):
    out = []
    for fam, mem, nn in sp.incidences:
        m = ",".join(str(x) for x in mem)
        if sp.label == "LP" or (sp.label == "BP" and fam == "balanced"):
            out.append(f"{fam}/{m}: n_unstable of the members next to it {nn[0]},{nn[1]}")
        else:
            out.append(f"{fam}/{m}: n_unstable before {nn[0]} after {nn[1]}")
    return "; ".join(out)


def print_specials(p, name, lo, hi, specials, notes, stats, elapsed, out=sys.stdout):
    print(f"# {p.source}\n#   {p.describe()}", file=out)
    print(f"# special points along {name} in ({lo!r}, {hi!r}); located at {WORK_DPS} digits, again at "
          f"{VERIFY_DPS} (digits = agreement); scan at {SCAN_DPS} digits, {stats.get('samples', 0)} samples; "
          f"{elapsed:.1f} s", file=out)
    if balls_identical(p):
        print("# identical balls: a point on balanced/1 (opposite/1) is also on its swap image /2", file=out)
    for n in notes:
        print(f"# {n}", file=out)
    if stats.get("orlando_mismatch"):
        print(f"# WARNING: Hurwitz and Orlando signs of Delta_7 differ at {stats['orlando_mismatch']} samples", file=out)
    if stats.get("runaway"):
        print("# WARNING: sample budget exhausted in a segment", file=out)
    k = 0
    for sp in specials:
        if sp.label == "NS":
            continue
        k += 1
        fam = sp.family + "/" + ",".join(str(m) for m in sp.members)
        # enough digits to tell it from a special point close by (degenerate scenes)
        gap = min([abs(o.v - sp.v) / abs(sp.v) for o in specials if o is not sp and o.v != sp.v] + [mpf(1)])
        ndig = 20 if gap > mpf(10) ** -14 else min(VERIFY_DPS - 5, int(-mp.log10(gap)) + 8)
        extra = ""
        if sp.label == "BP":
            fam = "balanced/1,2 + " + "/".join(str(x) for x in getattr(sp, "through", (sp.other, "?")))
        print(f"\n[{k}] {sp.label} {fam}  {name} = {mp.nstr(sp.v, ndig)}  (digits {sp.digits:.0f})", file=out)
        print(f"    {_fmt_state(sp.state)}", file=out)
        if sp.label == "HB":
            extra = f"    w_H = {mp.nstr(sp.freq, 20)} rad/s"
            if sp.lyap is not None:
                l1, dg = sp.lyap
                extra += (f"; first Lyapunov coefficient l1 = {mp.nstr(l1, 6)} "
                          f"({'supercritical' if l1 < 0 else 'subcritical'}; {dg:.0f} digits)")
            print(extra, file=out)
        print(f"    {_fmt_inc(sp)}", file=out)
        if sp.check:
            print(f"    check: {sp.check}", file=out)
        for n in sp.notes:
            print(f"    note: {n}", file=out)
    ns = [sp for sp in specials if sp.label == "NS"]
    if ns:
        print("\n# neutral saddles (Delta_7 = 0 with a real pair +-r: NOT special points)", file=out)
        for sp in ns:
            print(f"#   NS {sp.family}/{','.join(str(m) for m in sp.members)} {name} = {mp.nstr(sp.v, 20)} "
                  f"r = {mp.nstr(abs(sp.crit.real), 6)}  n_unstable {sp.incidences[0][2][0]} -> "
                  f"{sp.incidences[0][2][1]}", file=out)
    other = [sp for sp in specials if sp.label not in ("LP", "BP", "HB", "NS")]
    for sp in other:
        print(f"# WARNING unclassified Delta_7 zero {sp.family}/{sp.members} at {mp.nstr(sp.v, 20)}", file=out)


# ----------------------------------------------------------------------------------
# comparison with the C++ program's special-points CSV
# ----------------------------------------------------------------------------------
# State tolerance for identifying a row with a reference point (not an accuracy test:
# the parameter and the frequency carry that). At a fold the state moves like the square
# root of the parameter error, so a fold found to 1e-8 can sit 1e-4 away in the state;
# distinct points with the same label and parameter differ by O(1).
STATE_TOL = 1e-3
CSV_COLUMNS = ("branch", "label", "q1", "q2", "beta1", "beta2", "q_abs", "family", "frequency", "re", "im",
               "lyapunov", "converged", "n_unstable_before", "n_unstable_after")


def read_special_csv(path, name):
    with open(path, newline="") as fh:
        lines = [ln for ln in fh if ln.strip() and not ln.lstrip().startswith("#")]
    if not lines:
        raise InputError(f"{path}: empty (no header row)")
    rows = list(csv.DictReader(lines))
    header = next(csv.reader(lines[:1]))
    missing = [c for c in CSV_COLUMNS + (name,) if c not in header]
    if missing:
        raise InputError(f"{path}: CSV lacks columns {missing}")
    return rows


def compare(csv_path, p, name, lo, hi, rtol=1e-8, state_tol=STATE_TOL, out=sys.stdout, specials=None, notes=()):
    rows = read_special_csv(csv_path, name)
    if specials is None:
        specials, notes, stats = special_points(p, name, lo, hi)
    ref = [sp for sp in specials if sp.label in LABELS]
    ns = [sp for sp in specials if sp.label == "NS"]
    ok = True
    print(f"# reference: {p.source}\n#   {p.describe()}", file=out)
    print(f"# {len(ref)} reference special points along {name} in ({lo!r}, {hi!r}); "
          f"rtol {rtol:g} on {name} and w_H; state tolerance {state_tol:g}", file=out)
    for n in notes:
        print(f"# reference note: {n}", file=out)

    # reference points closer than rtol to each other cannot be told apart by the C++
    # program: they form one cluster, found if any of them is, any of their labels allowed
    clusters = []
    for sp in ref:
        for cl in clusters:
            if any(abs(sp.v - o.v) <= rtol * abs(o.v) and same_point(p, sp.state, o.state, state_tol)[0] for o in cl):
                cl.append(sp)
                break
        else:
            clusters.append([sp])
    found = [[] for _ in clusters]
    invented = []
    with mp.workdps(WORK_DPS):
        for n, r in enumerate(rows, 1):
            label = r["label"].strip()
            if label == "EP":
                continue
            where = f"row {n} (branch {r['branch'].strip()}, {label}, {r['family'].strip()})"
            if label == "MX":
                print(f"FAIL {where}: MX (continuation failed) at {name} = {r[name].strip()}", file=out)
                ok = False
                continue
            if label not in LABELS:
                print(f"FAIL {where}: unknown label {label!r}", file=out)
                ok = False
                continue
            try:
                v = mpf(float(r[name]))
                st = [mpf(float(r[k])) for k in ("q1", "q2", "beta1", "beta2")]
                # Empty fields are "not defined here" (frequency off HB points, lyapunov off
                # located HB points), never a sentinel 0.
                freq = float(r["frequency"]) if r["frequency"].strip() else None
                lyap = float(r["lyapunov"]) if r["lyapunov"].strip() else None
                conv = int(float(r["converged"]))
                nb, na = int(float(r["n_unstable_before"])), int(float(r["n_unstable_after"]))
            except (ValueError, TypeError) as ex:
                print(f"FAIL {where}: unreadable number: {ex}", file=out)
                ok = False
                continue
            if not all(math.isfinite(x) for x in [float(v)] + [float(x) for x in st]
                       + [x for x in (freq, lyap) if x is not None]):
                print(f"FAIL {where}: non-finite value", file=out)
                ok = False
                continue
            if abs(v - lo) <= rtol * abs(lo) or abs(v - hi) <= rtol * abs(hi) or not mpf(lo) < v < mpf(hi):
                print(f"NOTE {where}: at an end of or outside the interval ({name} = {r[name].strip()}), "
                      "not checked", file=out)
                continue
            cand = []
            for ci, cl in enumerate(clusters):
                for sp in cl:
                    match, d = same_point(p, st, sp.state, state_tol)
                    if abs(v - sp.v) <= rtol * abs(sp.v) and match:
                        cand.append((ci, sp, d))
            same = [c for c in cand if c[1].label == label or label in {s.label for s in clusters[c[0]]}]
            if not same:
                if cand:
                    sp = cand[0][1]
                    print(f"FAIL {where}: label {label}, reference says {sp.label} at {name} = "
                          f"{mp.nstr(sp.v, 17)}", file=out)
                else:
                    close = [s for s in ns if abs(v - s.v) <= rtol * abs(s.v)]
                    why = (" (a neutral saddle: real pair +-r, not a Hopf point)" if close else "")
                    near = [s for cl in clusters for s in cl
                            if s.label == label and same_point(p, st, s.state, state_tol)[0]]
                    if near and not close:
                        s = min(near, key=lambda s: abs(v - s.v))
                        why = (f" (nearest reference {label} with this state at {name} = {mp.nstr(s.v, 17)}, "
                               f"rel err {float(abs(v - s.v) / abs(s.v)):.1e})")
                    print(f"FAIL {where}: invented: no reference {label} at {name} = {r[name].strip()} with "
                          f"state ({r['q1'].strip()}, {r['q2'].strip()}, {r['beta1'].strip()}, "
                          f"{r['beta2'].strip()}){why}", file=out)
                    invented.append(n)
                ok = False
                continue
            ci, sp, d = min(same, key=lambda c: abs(v - c[1].v) / abs(c[1].v))
            rel = abs(v - sp.v) / abs(sp.v)
            notes, good = [f"{name} rel err {float(rel):.1e}", f"state dist {float(d):.1e}"], True
            if label == "HB":
                if sp.freq is None:
                    good = False
                    notes.append("reference point is not a Hopf point")
                elif freq is None:
                    good = False
                    notes.append("NO FREQUENCY given on an HB row")
                else:
                    fe = abs(mpf(freq) - sp.freq) / sp.freq
                    notes.append(f"w_H rel err {float(fe):.1e}")
                    if fe > rtol:
                        good = False
                        notes.append(f"FREQUENCY got {freq!r} ref {mp.nstr(sp.freq, 17)}")
                if sp.lyap is not None and lyap is not None:
                    l1, dg = sp.lyap
                    if dg >= 3 and mp.sign(l1) != mp.sign(lyap):
                        good = False
                        notes.append(f"LYAPUNOV SIGN got {lyap!r} ref {mp.nstr(l1, 6)}")
                    else:
                        notes.append(f"l1 rel diff {float(abs(mpf(lyap) - l1) / abs(l1)):.1e}")
                elif sp.lyap is not None:
                    notes.append("no l1 given")
            if conv != 1:
                good = False
                notes.append("NOT CONVERGED (converged = 0)")
            # instability counts: along the direction of travel, so compared as unordered
            # pairs; at a BP a branch may leave along any incident branch
            fam = r["family"].strip()
            cl = clusters[ci]
            fams = {f for s in cl for f, _, _ in s.incidences}
            if fam not in fams:
                # a BP's state belongs to every incident family (q = 0 and b1 = b2): any is right
                good = False
                notes.append(f"FAMILY {fam}, reference {'/'.join(sorted(fams))}")
            if sp.label == "BP" or len(cl) > 1:
                # a branch may arrive and leave along any incident branch (or any point of
                # a cluster): each count must be one of theirs
                vals = {x for s in cl for nn in s.n_pairs() for x in nn if x is not None}
                okc = nb in vals and na in vals
                expect = f"values {sorted(vals)}"
            else:
                allowed = {tuple(sorted(nn)) for nn in sp.n_pairs(fam) if None not in nn}
                okc = tuple(sorted((nb, na))) in allowed
                expect = f"{sorted(allowed)} (unordered)"
            notes.append(f"n_unstable {nb}->{na}")
            if not okc:
                good = False
                notes.append(f"N_UNSTABLE reference {expect}")
            if rel > rtol:
                good = False
            found[ci].append(n)
            print(f"{'PASS' if good else 'FAIL'} {where}: {sp.label} at {name} = {mp.nstr(sp.v, 17)}: "
                  + "; ".join(notes), file=out)
            ok = ok and good
    for ci, cl in enumerate(clusters):
        labels = "/".join(sp.label for sp in cl)
        desc = (f"{labels} {cl[0].family}/{','.join(str(m) for m in cl[0].members)} at {name} = "
                f"{mp.nstr(cl[0].v, 17)}")
        if len(cl) > 1:
            desc += f" (cluster of {len(cl)} points closer than rtol)"
        if found[ci]:
            print(f"PASS found {desc}: rows {', '.join(str(x) for x in found[ci])}", file=out)
        else:
            print(f"FAIL missed {desc}", file=out)
            ok = False
    print("PASS" if ok else "FAIL", file=out)
    return ok


# ----------------------------------------------------------------------------------
# CLI
# ----------------------------------------------------------------------------------
def main(argv=None):
    global BASE_POINTS, NEAR
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--param", required=True, help="omega U k c M_r kappa m l d mu mu_c mu_s v_s (ball ones: "
                                                   "both balls, or m1, m2, ...)")
    ap.add_argument("--from", dest="lo", type=float, required=True)
    ap.add_argument("--to", dest="hi", type=float, required=True)
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE")
    ap.add_argument("--compare", metavar="SPECIAL_CSV", help="check the C++ program's special-points CSV")
    ap.add_argument("--rtol", type=float, default=1e-8)
    ap.add_argument("--state-tol", type=float, default=STATE_TOL)
    ap.add_argument("--no-lyapunov", action="store_true", help="skip the first Lyapunov coefficients")
    ap.add_argument("--grid", type=int, default=BASE_POINTS,
                    help=f"base scan points per segment (default {BASE_POINTS}); with --probe-all for a "
                         "brute-force rerun that the default scan must agree with")
    ap.add_argument("--probe-all", action="store_true", help="probe the middle of every scan interval")
    a = ap.parse_args(argv)
    BASE_POINTS = a.grid
    if a.probe_all:
        NEAR = mpf("inf")
    try:
        p = R.load_scene(a.scene, a.set)
        lo, hi = min(a.lo, a.hi), max(a.lo, a.hi)
        t0 = time.time()
        if a.compare:
            read_special_csv(a.compare, a.param)          # bad input fails before the long computation
            sp, notes, stats = special_points(p, a.param, lo, hi, lyapunov=not a.no_lyapunov)
            ok = compare(a.compare, p, a.param, lo, hi, a.rtol, a.state_tol, specials=sp, notes=notes)
            print(f"# reference computed in {time.time() - t0:.1f} s")
            return 0 if ok else 1
        sp, notes, stats = special_points(p, a.param, lo, hi, lyapunov=not a.no_lyapunov,
                                          log=lambda s: print(s, file=sys.stderr))
        print_specials(p, a.param, lo, hi, sp, notes, stats, time.time() - t0)
        return 0
    except (R.InputError, OSError, KeyError, tomllib.TOMLDecodeError) as ex:
        print(f"mp_special: error: {type(ex).__name__}: {ex}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
