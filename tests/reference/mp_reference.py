#!/usr/bin/python3
"""High-precision (mpmath) reference for the two-ball ABU model of docs/model.md.

Independent of the C++ analyzer and of the numpy baseline: equilibria (model.md §5),
Jacobian at an equilibrium (§6) and its eigenvalues, all in mpmath at WORK_DPS
significant digits (80 by default; the module raises mp.dps to that on import).

Input convention: a scene's numbers are the IEEE doubles the TOML text parses to
(tomllib floats, or --set values through float()); they enter as mp.mpf(float),
which is exact. Everything after that is high-precision arithmetic, so the reference
is the exact model at the double inputs the C++ program also sees. Only j = 7/5
(rolling) is taken as the exact rational, not the double 1.4 (2e-17 relative apart).

    import mp_reference as R
    p = R.load_scene("data/scenes/default.toml", ["omega=1200"])
    for e in R.equilibria(p):
        lam = R.eigenvalues(R.jacobian(p, e.state))

CLI:
    mp_reference.py SCENE [--set NAME=VALUE ...] [--digits 30]
    mp_reference.py --compare CSV SCENE [--set NAME=VALUE ...] [--rtol 1e-8]
"""
import argparse
import csv
import itertools
import math
import sys
import tomllib

from mpmath import mp, mpf, mpc

WORK_DPS = 80          # working precision (significant decimal digits)
VERIFY_EXTRA_DPS = 40  # the verification rerun uses WORK_DPS + this
if mp.dps < WORK_DPS:
    mp.dps = WORK_DPS

LAWS = ("none", "viscous", "coulomb", "stribeck")
FAMILIES = ("balanced", "together", "opposite")
BALL_FRICTION_KEYS = ("mu", "d", "mu_c", "mu_s", "v_s")
GLOBAL_SYMBOLS = {"omega": "omega", "U": "U", "k": "k", "c": "c", "M_r": "Mr", "kappa": "kappa"}
BALL_SYMBOLS = ("m", "l", "r") + BALL_FRICTION_KEYS


class InputError(Exception):
    pass


# ----------------------------------------------------------------------------------
# parameters: stored as the Python floats (IEEE doubles) of the input; converted with
# mpf(float), exact at any precision, whenever they are used.
# ----------------------------------------------------------------------------------
class Ball:
    def __init__(self, m, l, r, rolling=True, mu=None, d=None, mu_c=None, mu_s=None, v_s=None):
        self.m, self.l, self.r = float(m), float(l), float(r)
        self.rolling = bool(rolling)
        self.mu, self.d, self.mu_c, self.mu_s, self.v_s = mu, d, mu_c, mu_s, v_s

    def j(self):
        """Rolling inertia factor, exact: 7/5 for a rolling solid sphere, 1 sliding."""
        return mpf(7) / 5 if self.rolling else mpf(1)


class Params:
    def __init__(self, Mr, k, c, U, omega, balls, law="none", kappa=None, source=""):
        if law not in LAWS:
            raise InputError(f"unknown friction law {law!r} (one of {', '.join(LAWS)})")
        if len(balls) != 2:
            raise InputError(f"the reference handles exactly 2 balls, got {len(balls)}")
        self.Mr, self.k, self.c, self.U, self.omega = (float(v) for v in (Mr, k, c, U, omega))
        self.balls = balls
        self.law = law
        self.kappa = None if kappa is None else float(kappa)
        self.source = source

    # mp views (exact conversions, evaluated at the current precision)
    def mp(self, name):
        return mpf(getattr(self, name))

    def M(self):
        return mpf(self.Mr) + sum(mpf(b.m) for b in self.balls)

    def ml(self, i):
        return mpf(self.balls[i].m) * mpf(self.balls[i].l)

    def KC(self):
        w = mpf(self.omega)
        return mpf(self.k) - w * w * self.M(), mpf(self.c) * w

    def displacement_scale(self):
        """(U + m1 l1 + m2 l2) / M, the rotor displacement the ball set and unbalance make."""
        return (mpf(self.U) + self.ml(0) + self.ml(1)) / self.M()

    def check(self):
        def need(name, v, positive):
            if v is None or not math.isfinite(v) or (v <= 0 if positive else v < 0):
                raise InputError(f"{name} must be {'> 0' if positive else '>= 0'} (got {v})")
        for n in ("Mr", "k", "omega"):
            need(n, getattr(self, n), True)
        for n in ("c", "U"):
            need(n, getattr(self, n), False)
        for i, b in enumerate(self.balls, 1):
            need(f"m{i}", b.m, True)
            need(f"l{i}", b.l, True)
            need(f"r{i}", b.r, True)
            if self.law == "viscous":
                need(f"d{i}", b.d, False)
            elif self.law == "coulomb":
                need(f"mu{i}", b.mu, False)
            elif self.law == "stribeck":
                need(f"mu_c{i}", b.mu_c, False)
                need(f"mu_s{i}", b.mu_s, False)
                need(f"v_s{i}", b.v_s, True)
        if self.law in ("coulomb", "stribeck"):
            need("kappa", self.kappa, True)

    def describe(self):
        b = self.balls
        s = (f"M_r={self.Mr!r} k={self.k!r} c={self.c!r} U={self.U!r} omega={self.omega!r} "
             f"law={self.law}")
        if self.law in ("coulomb", "stribeck"):
            s += f" kappa={self.kappa!r}"
        for i, bi in enumerate(b, 1):
            s += f"\n#   ball {i}: m={bi.m!r} l={bi.l!r} j={'7/5' if bi.rolling else '1'}"
            for key in BALL_FRICTION_KEYS:
                v = getattr(bi, key)
                if v is not None and self._law_uses(key):
                    s += f" {key}={v!r}"
        return s

    def _law_uses(self, key):
        return {"mu": "coulomb", "d": "viscous"}.get(key, "stribeck") == self.law


def _num(v, where):
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise InputError(f"{where}: expected a number, got {v!r}")
    return float(v)


def load_scene(path, overrides=()):
    """Reads a TOML scene (SI units) and applies 'NAME=VALUE' overrides (model.md symbols)."""
    with open(path, "rb") as fh:
        doc = tomllib.load(fh)
    rolling = doc.get("rolling", True)
    rotor = doc.get("rotor", {})
    fr = doc.get("friction", {})
    law = fr.get("law", "none")
    balls = []
    for i, bt in enumerate(doc.get("ball", []), 1):
        kw = {}
        for key in BALL_FRICTION_KEYS:
            v = bt.get(key, fr.get(key))
            kw[key] = None if v is None else _num(v, f"ball {i} {key}")
        balls.append(Ball(_num(bt["mass"], f"ball {i} mass"), _num(bt["race_radius"], f"ball {i} race_radius"),
                          _num(bt["radius"], f"ball {i} radius"), bt.get("rolling", rolling), **kw))
    kappa = fr.get("kappa")
    p = Params(_num(rotor["mass"], "rotor.mass"), _num(rotor["stiffness"], "rotor.stiffness"),
               _num(rotor.get("damping", 0.0), "rotor.damping"), _num(rotor["unbalance"], "rotor.unbalance"),
               _num(doc["speed"]["omega"], "speed.omega"), balls, law,
               None if kappa is None else _num(kappa, "friction.kappa"), source=str(path))
    for ov in overrides:
        apply_override(p, ov)
    p.check()
    return p


def apply_override(p, assignment):
    if "=" not in assignment:
        raise InputError(f"--set expects NAME=VALUE, got {assignment!r}")
    name, value = assignment.split("=", 1)
    name = name.strip()
    try:
        v = float(value)
    except ValueError:
        raise InputError(f"--set {name}: not a number: {value!r}") from None
    if name in GLOBAL_SYMBOLS:
        setattr(p, GLOBAL_SYMBOLS[name], v)
        return
    base, idx = name, None
    if name and name[-1].isdigit():
        base, idx = name[:-1], int(name[-1])
    if base not in BALL_SYMBOLS or (idx is not None and not 1 <= idx <= len(p.balls)):
        raise InputError(f"--set: unknown parameter {name!r}")
    attr = {"m": "m", "l": "l", "r": "r"}.get(base, base)
    for i, b in enumerate(p.balls, 1):
        if idx is None or idx == i:
            setattr(b, attr, v)


# ----------------------------------------------------------------------------------
# friction (model.md §4): force on ball i along +beta_i, and its slope at bdot = 0
# ----------------------------------------------------------------------------------
def friction_force(p, i, bd):
    b = p.balls[i]
    w = mpf(p.omega)
    N = p.ml(i) * w * w
    if p.law == "none":
        return mpf(0)
    if p.law == "viscous":
        return -mpf(b.d) * mpf(b.l) * bd
    at = 2 / mp.pi * mp.atan(mpf(p.kappa) * bd)
    if p.law == "coulomb":
        return -mpf(b.mu) * N * at
    mu_c, mu_s, v_s = mpf(b.mu_c), mpf(b.mu_s), mpf(b.v_s)
    return -N * (mu_c + (mu_s - mu_c) * mp.exp(-(bd / v_s) ** 2)) * at


def friction_slope0(p, i):
    """dF_i/dbdot_i at bdot_i = 0 (the exp factor of stribeck is 1 there, its derivative 0)."""
    b = p.balls[i]
    w = mpf(p.omega)
    N = p.ml(i) * w * w
    if p.law == "none":
        return mpf(0)
    if p.law == "viscous":
        return -mpf(b.d) * mpf(b.l)
    mu = mpf(b.mu) if p.law == "coulomb" else mpf(b.mu_s)
    return -(2 / mp.pi) * mu * N * mpf(p.kappa)


# ----------------------------------------------------------------------------------
# the model: A(beta) sdd = b(s, sdot)  (model.md §3, ball equations multiplied by l_i)
# ----------------------------------------------------------------------------------
def mass_matrix(p, b1, b2):
    M = p.M()
    A = mp.zeros(4, 4)
    A[0, 0] = A[1, 1] = M
    for i, be in enumerate((b1, b2)):
        ml = p.ml(i)
        A[0, 2 + i] = A[2 + i, 0] = -ml * mp.sin(be)
        A[1, 2 + i] = A[2 + i, 1] = ml * mp.cos(be)
        A[2 + i, 2 + i] = p.balls[i].j() * ml * mpf(p.balls[i].l)
    return A


def rhs(p, x):
    """b(s, sdot) for x = (q1, q2, b1, b2, q1d, q2d, b1d, b2d)."""
    q1, q2, b1, b2, q1d, q2d, b1d, b2d = x
    w = mpf(p.omega)
    M, k, c = p.M(), mpf(p.k), mpf(p.c)
    P1 = 2 * w * q2d + w * w * q1      # q1dd - a1
    P2 = -2 * w * q1d + w * w * q2     # q2dd - a2
    r0 = M * P1 - c * (q1d - w * q2) - k * q1 + w * w * mpf(p.U)
    r1 = M * P2 - c * (q2d + w * q1) - k * q2
    rb = []
    for i, (be, bd) in enumerate(((b1, b1d), (b2, b2d))):
        ml = p.ml(i)
        sb, cb = mp.sin(be), mp.cos(be)
        r0 += ml * (bd + w) ** 2 * cb
        r1 += ml * (bd + w) ** 2 * sb
        rb.append(mpf(p.balls[i].l) * friction_force(p, i, bd) + ml * (-P1 * sb + P2 * cb))
    return [r0, r1, rb[0], rb[1]]


def vector_field(p, x):
    """f(x) = (sdot, A(beta)^-1 b(s, sdot))."""
    A = mass_matrix(p, x[2], x[3])
    sdd = mp.lu_solve(A, mp.matrix(rhs(p, x)))
    return list(x[4:]) + [sdd[i] for i in range(4)]


def db_ds_dsdot(p, state):
    """(db/ds, db/dsdot) at sdot = 0, derived by hand from rhs() (see the comments)."""
    q1, q2, b1, b2 = state[:4]
    w = mpf(p.omega)
    w2 = w * w
    M, k, c = p.M(), mpf(p.k), mpf(p.c)
    Gs = mp.zeros(4, 4)
    Gv = mp.zeros(4, 4)
    # rotor rows: M w^2 q - k q and the c w cross terms; gyroscopic 2 w M; damping -c
    Gs[0, 0] = Gs[1, 1] = M * w2 - k
    Gs[0, 1] = c * w
    Gs[1, 0] = -c * w
    Gv[0, 0] = Gv[1, 1] = -c
    Gv[0, 1] = 2 * w * M
    Gv[1, 0] = -2 * w * M
    for i, be in enumerate((b1, b2)):
        ml = p.ml(i)
        sb, cb = mp.sin(be), mp.cos(be)
        # d/dbeta of ml (bd + w)^2 (cos, sin) at bd = 0; d/dbd gives 2 ml w (cos, sin)
        Gs[0, 2 + i] = -ml * w2 * sb
        Gs[1, 2 + i] = ml * w2 * cb
        Gv[0, 2 + i] = 2 * ml * w * cb
        Gv[1, 2 + i] = 2 * ml * w * sb
        # ball row: l F + ml (-(w^2 q1 + 2 w q2d) sin b + (w^2 q2 - 2 w q1d) cos b)
        Gs[2 + i, 0] = -ml * w2 * sb
        Gs[2 + i, 1] = ml * w2 * cb
        Gs[2 + i, 2 + i] = -ml * w2 * (q1 * cb + q2 * sb)
        Gv[2 + i, 0] = -2 * w * ml * cb
        Gv[2 + i, 1] = -2 * w * ml * sb
        Gv[2 + i, 2 + i] = mpf(p.balls[i].l) * friction_slope0(p, i)
    return Gs, Gv


def jacobian(p, state):
    """8x8 J = [[0, I], [A^-1 db/ds, A^-1 db/dsdot]] at an equilibrium (model.md §6).
    state: (q1, q2, b1, b2) or the full 8-vector (its velocities must be zero)."""
    state = [mpf(v) if not isinstance(v, mpf) else v for v in list(state)[:4]]
    Gs, Gv = db_ds_dsdot(p, state)
    Ainv = mp.inverse(mass_matrix(p, state[2], state[3]))
    P, Q = Ainv * Gs, Ainv * Gv
    J = mp.zeros(8, 8)
    for r in range(4):
        J[r, 4 + r] = 1
        for col in range(4):
            J[4 + r, col] = P[r, col]
            J[4 + r, 4 + col] = Q[r, col]
    return J


def sort_key(z):
    return (-z.real, -z.imag)


def sort_eigenvalues(ev, rel=None):
    """Real part descending, then imaginary part descending. Real parts equal to `rel`
    relative to the spectrum's largest modulus count as equal (conjugate pairs, whose
    computed real parts differ by rounding), so the imaginary part decides there."""
    ev = sorted(ev, key=sort_key)
    if not ev:
        return ev
    tol = (mpf(10) ** (-(mp.dps - 10)) if rel is None else mpf(rel)) * max(abs(z) for z in ev)
    out, group = [], [ev[0]]
    for z in ev[1:]:
        if group[-1].real - z.real <= tol:
            group.append(z)
        else:
            out += sorted(group, key=lambda v: -v.imag)
            group = [z]
    return out + sorted(group, key=lambda v: -v.imag)


def eigenvalues(J):
    """All eigenvalues (mp.eig, Hessenberg QR at the current precision), sorted by real
    part descending, then imaginary part descending. J is real, so an imaginary part
    below rounding level (10^(10 - dps) |lambda|) is set to exactly 0."""
    ev = []
    for z in mp.eig(J, left=False, right=False):
        z = mpc(z)
        if abs(z.imag) <= mpf(10) ** (-(mp.dps - 10)) * abs(z):
            z = mpc(z.real, 0)
        ev.append(z)
    return sort_eigenvalues(ev)


# ----------------------------------------------------------------------------------
# equilibria (model.md §5)
# ----------------------------------------------------------------------------------
def wrap(a):
    t = 2 * mp.pi
    a = mp.fmod(a, t)
    if a < 0:
        a += t
    if a >= t:
        a -= t
    return a


class Equilibrium:
    def __init__(self, family, q1, q2, b1, b2, flags=()):
        self.family = family
        self.q1, self.q2 = q1, q2
        self.b1, self.b2 = wrap(b1), wrap(b2)
        self.flags = set(flags)
        self.residual = None
        self.newton_steps = 0

    @property
    def state(self):
        return [self.q1, self.q2, self.b1, self.b2]

    @property
    def is_set(self):
        return "set" in self.flags

    def __repr__(self):
        return (f"Equilibrium({self.family}, q=({mp.nstr(self.q1, 17)}, {mp.nstr(self.q2, 17)}), "
                f"beta=({mp.nstr(self.b1, 17)}, {mp.nstr(self.b2, 17)}), flags={sorted(self.flags)})")


def _q_of(p, K, C, weighted_sum):
    """q from the two linear rotor equations: (K + iC) q = w^2 (U + sum m_i l_i e^{i b_i})."""
    w = mpf(p.omega)
    qc = w * w * (mpf(p.U) + weighted_sum) / mpc(K, C)
    return qc.real, qc.imag


def _line_family(p, K, C, D, family):
    """Roots of K U sin b + C U cos b + C D = 0 (D = m1l1 + m2l2 for 'together', m1l1 - m2l2
    for 'opposite', b2 = b1 + pi), each with q = w^2 (U + D e^{ib}) / (K + iC)."""
    U = mpf(p.U)
    off = 0 if family == "together" else mp.pi
    R = mp.hypot(K, C)
    out = []
    if R == 0:
        return out                                   # K = C = 0: no bounded rotor state
    merge = U == abs(D) and U > 0
    if U == 0:
        if C == 0 and D != 0:                        # every b: a circle (rotational invariance)
            q1, q2 = _q_of(p, K, C, D)
            out.append(Equilibrium(family, q1, q2, 0, off, {"set"}))
        return out                                   # (D = 0: it is the balanced circle)
    x = -C * D / (U * R)
    if abs(x) > 1:
        return out
    phi = mp.atan2(C, K)
    a = mp.asin(x)
    roots = [(-phi + a, set())] if abs(x) == 1 else [(-phi + a, set()), (mp.pi - phi - a, set())]
    if abs(x) == 1:
        roots[0][1].add("double_root")
    for b, flags in roots:
        q1, q2 = _q_of(p, K, C, D * mp.expj(b))
        if merge and abs(U + D * mp.expj(b)) <= mpf(10) ** (10 - mp.dps) * U:
            flags = flags | {"merge"}             # this root is the balanced point (q = 0)
        out.append(Equilibrium(family, q1, q2, b, b + off, flags))
    return out


def _balanced(p):
    U = mpf(p.U)
    a, b = p.ml(0), p.ml(1)
    if U == 0:
        return [Equilibrium("balanced", mpf(0), mpf(0), 0, mp.pi, {"set"})] if a == b else []
    x = (b * b - a * a - U * U) / (2 * a * U)        # cos b1 from |a e^{ib1} + U| = b
    if abs(x) > 1:
        return []
    th = mp.acos(x)
    pts = [th] if abs(x) == 1 else [th, -th]
    out = []
    for b1 in pts:
        z = -(a * mp.expj(b1) + U) / b
        b2 = mp.atan2(z.imag, z.real)
        out.append(Equilibrium("balanced", mpf(0), mpf(0), b1, b2, {"merge"} if abs(x) == 1 else set()))
    return out


def static_residual(p, state):
    return rhs(p, list(state) + [mpf(0)] * 4)


def residual_norm(p, state):
    """max over the 4 static equations of |b_i| / (the size of that equation's terms)."""
    q1, q2 = state[0], state[1]
    w2 = mpf(p.omega) ** 2
    qn = mp.hypot(q1, q2)
    Q = p.displacement_scale()
    S = p.ml(0) + p.ml(1)
    scale_rotor = w2 * (mpf(p.U) + S) + (mpf(p.k) + w2 * p.M() + mpf(p.c) * mp.sqrt(w2)) * qn
    r = static_residual(p, state)
    out = max(abs(r[0]), abs(r[1])) / scale_rotor
    for i in range(2):
        out = max(out, abs(r[2 + i]) / (p.ml(i) * w2 * (qn + Q)))
    return out


def newton_polish(p, e, extra_dps=20, maxit=60):
    """Newton on the 4 static equations b(s, 0) = 0 at mp.dps + extra_dps."""
    if e.flags & {"set", "merge", "double_root"}:
        # the static Jacobian is singular there (along the set / at the fold); the closed
        # form is already exact to working precision
        e.residual = residual_norm(p, e.state)
        return e
    target = mpf(10) ** (-(mp.dps + 5))
    with mp.extradps(extra_dps):
        s = [mpf(v) for v in e.state]
        Q = p.displacement_scale()
        for it in range(maxit):
            r = static_residual(p, s)
            Gs, _ = db_ds_dsdot(p, s)
            try:
                ds = mp.lu_solve(Gs, -mp.matrix(r))
            except ZeroDivisionError:       # singular static Jacobian: keep the closed form
                e.flags.add("newton_singular")
                break
            s = [s[i] + ds[i] for i in range(4)]
            e.newton_steps = it + 1
            size = max(abs(ds[0]) / (Q + mp.hypot(s[0], s[1])), abs(ds[1]) / (Q + mp.hypot(s[0], s[1])),
                       abs(ds[2]), abs(ds[3]))
            if size < target:
                break
        else:
            e.flags.add("newton_not_converged")
    e.q1, e.q2 = +s[0], +s[1]
    if e.family == "balanced" and mp.hypot(e.q1, e.q2) <= mpf(10) ** -mp.dps * p.displacement_scale():
        e.q1 = e.q2 = mpf(0)           # exactly 0 at a balanced point; Newton left rounding noise
    e.b1, e.b2 = wrap(+s[2]), wrap(+s[3])
    e.residual = residual_norm(p, e.state)
    return e


def equilibria(p, polish=True):
    """All real equilibria of the two-ball model: balanced, together (b1 = b2), opposite
    (b2 = b1 + pi). Set-valued cases (U = 0) give one representative with b1 = 0 and flag
    'set'; exact merges (U = |m1l1 +- m2l2|) are flagged 'merge'; K = C = 0 leaves only
    the balanced points. Angles in [0, 2 pi)."""
    K, C = p.KC()
    a, b = p.ml(0), p.ml(1)
    eqs = _balanced(p)
    if not (K == 0 and C == 0):
        eqs += _line_family(p, K, C, a + b, "together")
        eqs += _line_family(p, K, C, a - b, "opposite")
    if polish:
        for e in eqs:
            newton_polish(p, e)
    order = {f: n for n, f in enumerate(FAMILIES)}
    eqs.sort(key=lambda e: (order[e.family], e.b1, e.b2))
    return eqs


# ----------------------------------------------------------------------------------
# full reference with a precision check: everything is recomputed at a higher precision
# and the difference bounds the error of the working-precision result.
# ----------------------------------------------------------------------------------
def solve(p, dps=WORK_DPS):
    with mp.workdps(dps):
        eqs = equilibria(p)
        for e in eqs:
            J = jacobian(p, e.state)
            e.J = J
            e.eig = eigenvalues(J)
            tr = sum(J[i, i] for i in range(8))
            e.trace_err = abs(sum(e.eig) - tr) / max(sum(abs(z) for z in e.eig), mpf(10) ** -300)
    return eqs


def _pair_min(a, b, zero=None, scale=None):
    """Permutation of b minimising the largest |a_k - b_perm(k)| / |a_k| (n <= 8).
    Reference values below `zero` are structural zeros: their cost is |b| / scale."""
    best, bestp = None, None
    def cost_of(x, y):
        if zero is not None and abs(x) < zero:
            return float(abs(y) / scale)
        return float(abs(x - y) / abs(x)) if x != 0 else float(abs(y))
    cost = [[cost_of(x, y) for y in b] for x in a]
    for perm in itertools.permutations(range(len(b))):
        c = max(cost[k][perm[k]] for k in range(len(a)))
        if best is None or c < best:
            best, bestp = c, perm
    return [b[k] for k in bestp]


def verified(p, dps=WORK_DPS):
    """solve() at dps and dps + VERIFY_EXTRA_DPS; each equilibrium gets .digits, the
    number of significant digits on which the two agree (state and every eigenvalue)."""
    lo = solve(p, dps)
    hi = solve(p, dps + VERIFY_EXTRA_DPS)
    if [e.family for e in lo] != [e.family for e in hi]:
        raise RuntimeError("equilibrium families differ between precisions")
    with mp.workdps(dps + VERIFY_EXTRA_DPS):
        for e, h in zip(lo, hi):
            d = max(abs(e.q1 - h.q1) + abs(e.q2 - h.q2), mpf(0)) / (p.displacement_scale() + mp.hypot(h.q1, h.q2))
            d = max(d, abs(e.b1 - h.b1), abs(e.b2 - h.b2))
            he = _pair_min(e.eig, h.eig) if len(e.eig) == len(h.eig) else h.eig
            scale = max(abs(z) for z in h.eig)
            for x, y in zip(e.eig, he):
                # a structurally zero eigenvalue (sets) is measured against the spectrum's size
                ref = abs(y) if abs(y) > mpf(10) ** (-dps // 2) * scale else scale
                d = max(d, abs(x - y) / ref)
            e.digits = float(-mp.log10(d)) if d > 0 else float(dps + VERIFY_EXTRA_DPS)
    return lo


def input_sensitivity(p, dps=40):
    """How much rounding one input moves the spectrum: for every input x (the model.md
    symbols the law uses), x -> x (1 + 2^-52); returns per equilibrium the largest
    relative change of any eigenvalue and the input responsible. A double-precision
    code that rounds its inputs once cannot beat this; rtol should stay ~10x above it."""
    import copy
    names = ["Mr", "k", "U", "omega"] + (["c"] if p.c else []) + \
        (["kappa"] if p.law in ("coulomb", "stribeck") else [])
    ball_keys = ["m", "l"] + {"none": [], "viscous": ["d"], "coulomb": ["mu"],
                              "stribeck": ["mu_c", "mu_s", "v_s"]}[p.law]
    base = solve(p, dps)
    worst = [(0.0, "") for _ in base]
    targets = [(None, n) for n in names] + [(i, k) for i in range(2) for k in ball_keys]
    for i, key in targets:
        q = copy.deepcopy(p)
        obj = q if i is None else q.balls[i]
        v = getattr(obj, key)
        if not v:
            continue
        setattr(obj, key, v * (1 + 2.0 ** -52))
        pert = solve(q, dps)
        if [e.family for e in pert] != [e.family for e in base]:
            continue                  # the equilibrium set itself changes: not a rounding effect
        with mp.workdps(dps):
            for n, (e, f) in enumerate(zip(base, pert)):
                scale = max(abs(z) for z in e.eig)
                g = _pair_min(e.eig, f.eig)
                d = max(float(abs(x - y) / max(abs(x), mpf(10) ** -30 * scale)) for x, y in zip(e.eig, g))
                if d > worst[n][0]:
                    worst[n] = (d, key if i is None else f"{key}{i + 1}")
    return [(e.family, d, who) for e, (d, who) in zip(base, worst)]


# ----------------------------------------------------------------------------------
# comparison with the C++ program's CSV
# ----------------------------------------------------------------------------------
# Tolerances of the state comparison (eigenvalues use --rtol, default 1e-8):
#   q: |q - q_ref| <= Q_TOL * ((U + m1l1 + m2l2)/M + |q_ref|). Closed forms in double give
#      ~1e-15; the worst legitimate conditioning in our scenes (k/|k - w^2 M| ~ 2e3 at c = 0
#      near w_n, cancellation U - S e^{ib} near a merge) costs < 1e-12. Absolute part: q = 0
#      exactly at balanced points; relative part: q grows by w^2 M/|K + iC| near resonance.
#   beta: |beta - beta_ref| (mod 2 pi) <= BETA_TOL rad. acos(U/2ml) at 1 - 1e-9 from a merge
#      amplifies a double's rounding by 1/sqrt(2e-9) ~ 2e4, i.e. to ~5e-12 rad.
#   Both leave >= 100x headroom over honest double arithmetic; a wrong branch or sign is O(1).
# Eigenvalues: |lambda_k - ref_k| <= rtol |ref_k| each; a structurally zero reference
#   eigenvalue (|ref| < 1e-30 max|ref|, only on U = 0 sets) needs |lambda| <= ZERO_TOL max|ref|,
#   what a double eigensolver gives for an exact zero (eps times the norm of the scaled J).
Q_TOL = 1e-10
BETA_TOL = 1e-9
ZERO_TOL = 1e-9


def read_csv(path):
    with open(path, newline="") as fh:
        lines = [ln for ln in fh if ln.strip() and not ln.lstrip().startswith("#")]
    rows = list(csv.DictReader(lines))
    need = ["family", "q1", "q2", "beta1", "beta2", "spectral_abscissa", "stable"] + \
           [f"{p}{k}" for k in range(1, 9) for p in ("re", "im")]
    if rows:
        missing = [c for c in need if c not in rows[0]]
        if missing:
            raise InputError(f"{path}: CSV lacks columns {missing}")
    elif lines:
        missing = [c for c in need if c not in next(csv.reader(lines[:1]))]
        if missing:
            raise InputError(f"{path}: CSV lacks columns {missing}")
    return rows


def _angdist(a, b):
    d = abs(wrap(a - b))
    return min(d, 2 * mp.pi - d)


def _digits(rel):
    return "exact" if rel == 0 else f"{-math.log10(rel):.1f}"


def compare(csv_path, p, rtol=1e-8, out=sys.stdout):
    ref = verified(p)
    rows = read_csv(csv_path)
    ok = True
    Qs = p.displacement_scale()
    print(f"# reference: {p.source}\n#   {p.describe()}", file=out)
    print(f"# rtol {rtol:g}; state: q {Q_TOL:g} x (scale + |q|), beta {BETA_TOL:g} rad", file=out)
    by_fam_ref = {f: [e for e in ref if e.family == f] for f in FAMILIES}
    by_fam_csv = {f: [] for f in FAMILIES}
    for n, r in enumerate(rows, 1):
        fam = r["family"].strip()
        if fam not in by_fam_csv:
            print(f"FAIL row {n}: unknown family {fam!r}", file=out)
            ok = False
            continue
        by_fam_csv[fam].append((n, r))
    merged = any("merge" in e.flags for e in ref)
    for fam in FAMILIES:
        R, C = by_fam_ref[fam], by_fam_csv[fam]
        if len(R) != len(C):
            msg = (f"{'WARN' if merged else 'FAIL'} {fam}: {len(C)} rows in the CSV, "
                   f"{len(R)} reference equilibria" + (" (exact merge: counts may differ)" if merged else ""))
            print(msg, file=out)
            ok = ok and merged
        # pair rows with reference points: nearest state (n <= 2, try all assignments)
        def dist(e, r):
            if e.is_set:
                return mpf(0)
            q1, q2 = mpf(float(r["q1"])), mpf(float(r["q2"]))
            return (mp.hypot(q1 - e.q1, q2 - e.q2) / (Qs + mp.hypot(e.q1, e.q2))
                    + _angdist(mpf(float(r["beta1"])), e.b1) + _angdist(mpf(float(r["beta2"])), e.b2))
        best = None
        m = min(len(R), len(C))
        for perm in itertools.permutations(range(len(R)), m):
            cost = sum(dist(R[perm[k]], C[k][1]) for k in range(m))
            if best is None or cost < best[0]:
                best = (cost, perm)
        for k in range(m):
            if not _compare_row(p, R[best[1][k]], C[k][0], C[k][1], rtol, out):
                ok = False
    print("PASS" if ok else "FAIL", file=out)
    return ok


def _compare_row(p, e, n, r, rtol, out):
    ok = True
    notes = []
    Qs = p.displacement_scale()
    try:
        vals = {key: float(r[key]) for key in r if key not in ("family", "pattern", None) and r[key] not in (None, "")}
    except ValueError as ex:
        print(f"FAIL row {n} ({e.family}): unreadable number: {ex}", file=out)
        return False
    if not all(math.isfinite(v) for k, v in vals.items() if k != "residual"):
        print(f"FAIL row {n} ({e.family}): non-finite value", file=out)
        return False
    label = f"row {n} {e.family:8s}" + (" [set]" if e.is_set else "") + (" [merge]" if "merge" in e.flags else "")
    # state
    if not e.is_set:
        dq = mp.hypot(mpf(vals["q1"]) - e.q1, mpf(vals["q2"]) - e.q2)
        qtol = Q_TOL * (Qs + mp.hypot(e.q1, e.q2))
        db = max(_angdist(mpf(vals["beta1"]), e.b1), _angdist(mpf(vals["beta2"]), e.b2))
        notes.append(f"dq/tol {float(dq / qtol):.1e} dbeta {float(db):.1e}")
        if dq > qtol or db > BETA_TOL:
            ok = False
            notes.append(f"STATE MISMATCH ref q=({mp.nstr(e.q1, 17)}, {mp.nstr(e.q2, 17)}) "
                         f"beta=({mp.nstr(e.b1, 17)}, {mp.nstr(e.b2, 17)})")
    # eigenvalues
    got = sort_eigenvalues([mpc(vals[f"re{k}"], vals[f"im{k}"]) for k in range(1, 9)], rel=1e-15)
    refl = e.eig
    scale = max(abs(z) for z in refl)
    zero = mpf(10) ** -30 * scale

    def errs(g):
        out_ = []
        for x, y in zip(g, refl):
            if abs(y) < zero:
                out_.append((float(abs(x) / scale), ZERO_TOL))
            else:
                out_.append((float(abs(x - y) / abs(y)), rtol))
        return out_
    er = errs(got)
    how = "sorted"
    if any(v > t for v, t in er):
        got2 = _pair_min(refl, got, zero, scale)
        er2 = errs(got2)
        if max(v / t for v, t in er2) < max(v / t for v, t in er):
            got, er, how = got2, er2, "min-distance"
    worst = max(v for v, t in er)
    bad = [k for k, (v, t) in enumerate(er) if v > t]
    notes.append(f"eig worst rel {worst:.1e} ({_digits(worst)} digits, {how} pairing)")
    if bad:
        ok = False
        for k in bad:
            notes.append(f"EIG {k + 1}: got {mp.nstr(got[k], 17)} ref {mp.nstr(refl[k], 17)}")
    # spectral abscissa and stability
    ab = max(z.real for z in refl)
    lam_ab = max(abs(z) for z in refl if z.real >= ab - rtol * abs(z))
    atol = rtol * lam_ab if lam_ab > zero else ZERO_TOL * scale
    if abs(mpf(vals["spectral_abscissa"]) - ab) > atol:
        ok = False
        notes.append(f"ABSCISSA got {vals['spectral_abscissa']!r} ref {mp.nstr(ab, 17)}")
    stable = int(vals["stable"])
    if abs(ab) <= atol:
        notes.append("stability undecidable at rtol (abscissa ~ 0): not checked")
    elif stable != int(ab < 0):
        ok = False
        notes.append(f"STABLE got {stable} ref {int(ab < 0)} (abscissa {mp.nstr(ab, 6)})")
    print(f"{'PASS' if ok else 'FAIL'} {label}: " + "; ".join(notes), file=out)
    return ok


# ----------------------------------------------------------------------------------
# CLI
# ----------------------------------------------------------------------------------
def print_reference(p, digits=30, out=sys.stdout):
    eqs = verified(p)
    K, C = p.KC()
    print(f"# {p.source}\n#   {p.describe()}", file=out)
    print(f"# working precision {WORK_DPS} digits, checked against {WORK_DPS + VERIFY_EXTRA_DPS}; "
          f"K = {mp.nstr(K, 17)}, C = {mp.nstr(C, 17)}", file=out)
    if not eqs:
        print("# no equilibria", file=out)
    for n, e in enumerate(eqs, 1):
        flags = f" flags={','.join(sorted(e.flags))}" if e.flags else ""
        print(f"\n[{n}] {e.family}{flags}  (verified digits {e.digits:.0f}, residual "
              f"{mp.nstr(e.residual, 3)}, trace check {mp.nstr(e.trace_err, 3)})", file=out)
        for name, v in (("q1", e.q1), ("q2", e.q2), ("beta1", e.b1), ("beta2", e.b2)):
            print(f"  {name:6s} = {mp.nstr(v, digits)}", file=out)
        ab = max(z.real for z in e.eig)
        marginal = abs(ab) <= mpf(10) ** (10 - WORK_DPS) * max(abs(z) for z in e.eig)
        verdict = "marginal: zero at working precision" if marginal else "stable" if ab < 0 else "unstable"
        print(f"  spectral abscissa = {mp.nstr(ab, digits)}  ({verdict})", file=out)
        for k, z in enumerate(e.eig, 1):
            print(f"  lambda{k} = {mp.nstr(z.real, digits):>{digits + 8}} {'+' if z.imag >= 0 else '-'} "
                  f"{mp.nstr(abs(z.imag), digits)} i", file=out)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                    help="override a parameter (omega U k c M_r m m1 m2 l l1 l2 mu mu1 mu2 d kappa mu_c mu_s v_s)")
    ap.add_argument("--compare", metavar="CSV", help="check the C++ program's equilibria CSV")
    ap.add_argument("--rtol", type=float, default=1e-8, help="eigenvalue relative tolerance (compare mode)")
    ap.add_argument("--digits", type=int, default=30, help="digits printed (reference mode)")
    ap.add_argument("--sensitivity", action="store_true",
                    help="also print how far a 1-ulp change of one input moves the eigenvalues")
    a = ap.parse_args(argv)
    try:
        p = load_scene(a.scene, a.set)
        if a.compare:
            return 0 if compare(a.compare, p, a.rtol) else 1
        print_reference(p, a.digits)
        if a.sensitivity:
            print("\n# input sensitivity: largest relative eigenvalue change for one input x(1 + 2^-52)")
            for n, (fam, d, who) in enumerate(input_sensitivity(p), 1):
                print(f"#   [{n}] {fam:8s} {d:.1e} (input {who})")
        return 0
    except (InputError, OSError, KeyError, tomllib.TOMLDecodeError) as ex:
        print(f"mp_reference: error: {type(ex).__name__}: {ex}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
