#!/usr/bin/python3
"""High-precision (mpmath) reference for the n-ball ABU model (n = 2..12), docs/model.md §3-§6, §13.

Independent of the C++ analyzer and of mp_reference.py (the two-ball reference, which it
does not import): equilibria, Jacobian and eigenvalues in mpmath at WORK_DPS significant
digits (80 by default; the module raises mp.dps to that on import).

Input convention (as mp_reference.py): a scene's numbers are the IEEE doubles the TOML text
parses to (tomllib floats, --set values through float(), total_mass / count as a double
division); they enter as mp.mpf(float), which is exact. Only j = 7/5 (rolling) is the exact
rational. So the reference is the exact model at the double inputs the C++ program sees.

What it computes:
  * isolated equilibria (q != 0), docs/model.md §13.2: every ball on the line of q,
    e^{i beta_i} = sigma_i e^{i phi}; one scalar equation per sign pattern sigma (sigma_1 = +1),
    K U sin phi + C U cos phi + C S_sigma = 0, members phi = r - delta, pi - r - delta.
    For n <= 4 a multistart Newton on the static equations from a grid (multistart()) must
    find the same set (completeness check, independent of the line argument);
  * the (2n+4)x(2n+4) Jacobian of §6, by hand (db_ds_dsdot); jacobian_fd() differentiates
    the full vector field numerically as a check; mp.eig eigenvalues;
  * balanced states (q = 0, W = U + sum m_i l_i e^{i beta_i} = 0, §13.4): Newton on W = 0 in
    two angles (polish_onto_B), the full spectrum, its structural zeros (|lambda| <
    ZERO_REL max|lambda|: n - 2 of them, 2(n - 2) with friction none) and the normal
    spectrum (the rest); deflated_spectrum() = eig(V_N^T J V_N) cross-checks it.

CLI:
    mp_reference_n.py SCENE [--set NAME=VALUE ...] [--digits 20] [--max-rows K] [--samples S]
    mp_reference_n.py SCENE --csv [--samples S]          reference rows in the CSV contract
    mp_reference_n.py --compare CSV SCENE [--set NAME=VALUE ...] [--rtol 1e-8] [--max-rows K]
Exit status: 0 pass, 1 mismatch, 2 bad input.
"""
import argparse
import csv
import math
import re
import sys
import time
import tomllib

from mpmath import mp, mpf, mpc

WORK_DPS = 80          # working precision (significant decimal digits)
VERIFY_EXTRA_DPS = 40  # the verification rerun uses WORK_DPS + this
if mp.dps < WORK_DPS:
    mp.dps = WORK_DPS

N_MIN, N_MAX = 2, 12
LAWS = ("none", "viscous", "coulomb", "stribeck")
BALL_FRICTION_KEYS = ("mu", "d", "mu_c", "mu_s", "v_s")
BALL_TABLE_KEYS = ("mass", "race_radius", "radius", "rolling") + BALL_FRICTION_KEYS
GLOBAL_SYMBOLS = {"omega": "omega", "U": "U", "k": "k", "c": "c", "M_r": "Mr", "kappa": "kappa"}
BALL_SYMBOL_RE = re.compile(r"^(m|l|r|mu|d|mu_c|mu_s|v_s)(\d*)$")
# structural zeros: |lambda| below this times max|lambda| at WORK_DPS. Rounding at 80 digits
# leaves exact zeros at ~1e-78 (semisimple) or ~1e-40 (the friction-none Jordan pairs, which
# split like sqrt(eps)); the smallest physical eigenvalues of our scenes are >= 7.6e-17 of the
# largest (n4_equal_coulomb_k1e6). 1e-30 sits between both with >= 10 orders of margin.
ZERO_REL = mpf(10) ** -30


class InputError(Exception):
    pass


# ----------------------------------------------------------------------------------
# parameters: the Python floats (IEEE doubles) of the input; mpf(float) when used.
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
        if not N_MIN <= len(balls) <= N_MAX:
            raise InputError(f"the reference handles {N_MIN}..{N_MAX} balls, got {len(balls)}")
        self.Mr, self.k, self.c, self.U, self.omega = (float(v) for v in (Mr, k, c, U, omega))
        self.balls = balls
        self.law = law
        self.kappa = None if kappa is None else float(kappa)
        self.source = source

    @property
    def n(self):
        return len(self.balls)

    @property
    def dim(self):
        return 2 * self.n + 4

    def M(self):
        return mpf(self.Mr) + sum(mpf(b.m) for b in self.balls)

    def ml(self, i):
        return mpf(self.balls[i].m) * mpf(self.balls[i].l)

    def KC(self):
        w = mpf(self.omega)
        return mpf(self.k) - w * w * self.M(), mpf(self.c) * w

    def capacity(self):
        """U + sum m_i l_i: the size of every term of W."""
        return mpf(self.U) + sum(self.ml(i) for i in range(self.n))

    def displacement_scale(self):
        """(U + sum m_i l_i) / M, the rotor displacement the ball set and unbalance make."""
        return self.capacity() / self.M()

    def structural_zero_count(self, betas=None):
        """Zero eigenvalues by construction at the balanced point betas (docs/model.md §13.4):
        dim ker dW (n - 2 generically, n - 1 where all balls are collinear), plus one Jordan
        partner (0, delta) -> (delta, 0) for every tangent delta that moves only balls whose
        friction slope at rest is 0: dim ker of dW restricted to those balls. So n - 2 for
        viscous / coulomb / stribeck with nonzero coefficients and 2(n - 2) for friction none.
        betas None: a generic (non-collinear) point."""
        idx_all = list(range(self.n))
        free = [i for i in idx_all if friction_slope0(self, i) == 0]

        def kernel_dim(idx):
            if not idx:
                return 0
            if betas is None:
                return len(idx) - min(2, len(idx))
            return len(idx) - dW_rank(self, betas, idx)
        return kernel_dim(idx_all) + kernel_dim(free)

    def check(self):
        def need(name, v, positive):
            if v is None or not math.isfinite(v) or (v <= 0 if positive else v < 0):
                raise InputError(f"{name} must be {'> 0' if positive else '>= 0'} (got {v})")
        for nm in ("Mr", "k", "omega"):
            need(nm, getattr(self, nm), True)
        for nm in ("c", "U"):
            need(nm, getattr(self, nm), False)
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

    def _law_keys(self):
        return {"none": (), "viscous": ("d",), "coulomb": ("mu",),
                "stribeck": ("mu_c", "mu_s", "v_s")}[self.law]

    def describe(self):
        s = (f"n={self.n} M_r={self.Mr!r} k={self.k!r} c={self.c!r} U={self.U!r} "
             f"omega={self.omega!r} law={self.law}")
        if self.law in ("coulomb", "stribeck"):
            s += f" kappa={self.kappa!r}"

        def ball_text(b):
            t = f"m={b.m!r} l={b.l!r} j={'7/5' if b.rolling else '1'}"
            for key in self._law_keys():
                t += f" {key}={getattr(b, key)!r}"
            return t
        texts = [ball_text(b) for b in self.balls]
        for t in dict.fromkeys(texts):          # one line per distinct ball, in first-seen order
            idx = [i for i, u in enumerate(texts, 1) if u == t]
            runs, start = [], idx[0]
            for a_, b_ in zip(idx, idx[1:] + [None]):
                if b_ != a_ + 1:
                    runs.append(f"{start}" if start == a_ else f"{start}-{a_}")
                    start = b_
            s += f"\n#   ball{'s' if len(idx) > 1 else ''} {','.join(runs)}: {t}"
        return s


def _num(v, where):
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise InputError(f"{where}: expected a number, got {v!r}")
    return float(v)


def _bool(v, where):
    if not isinstance(v, bool):
        raise InputError(f"{where}: expected true or false, got {v!r}")
    return v


def _warn_unknown(table, allowed, where):
    for key in table:
        if key not in allowed:
            print(f"mp_reference_n: warning: {where}: unknown key {key!r} ignored", file=sys.stderr)


def _ball_from(table, defaults, where, rolling):
    """One ball from a table of ball keys, missing keys taken from `defaults`."""
    def get(key):
        return table[key] if key in table else defaults.get(key)
    for key in ("mass", "race_radius", "radius"):
        if get(key) is None:
            raise InputError(f"{where}: missing '{key}'")
    kw = {}
    for key in BALL_FRICTION_KEYS:
        v = get(key)
        kw[key] = None if v is None else _num(v, f"{where} {key}")
    roll = get("rolling")
    return Ball(_num(get("mass"), f"{where} mass"), _num(get("race_radius"), f"{where} race_radius"),
                _num(get("radius"), f"{where} radius"),
                rolling if roll is None else _bool(roll, f"{where} rolling"), **kw)


def load_scene(path, overrides=()):
    """Reads a TOML scene (SI units), either form of the balls ([[ball]] tables or the
    [balls] ring shorthand with [[balls.override]]), and applies 'NAME=VALUE' overrides."""
    with open(path, "rb") as fh:
        doc = tomllib.load(fh)
    rolling = _bool(doc.get("rolling", True), "rolling")
    rotor = doc.get("rotor", {})
    fr = doc.get("friction", {})
    law = fr.get("law", "none")
    fr_defaults = {key: fr[key] for key in BALL_FRICTION_KEYS if key in fr}
    if "ball" in doc and "balls" in doc:
        raise InputError("give the balls either as [[ball]] tables or as [balls], not both")
    balls = []
    if "balls" in doc:
        ring = doc["balls"]
        if not isinstance(ring, dict):
            raise InputError("[balls] must be a table")
        _warn_unknown(ring, BALL_TABLE_KEYS + ("count", "total_mass", "override"), "[balls]")
        count = ring.get("count")
        if isinstance(count, bool) or not isinstance(count, int) or not N_MIN <= count <= N_MAX:
            raise InputError(f"[balls] count must be an integer {N_MIN}..{N_MAX} (got {count!r})")
        if ("mass" in ring) == ("total_mass" in ring):
            raise InputError("[balls] needs exactly one of 'mass' (per ball) and 'total_mass'")
        base = dict(fr_defaults)
        base.update({key: ring[key] for key in BALL_TABLE_KEYS if key in ring})
        if "total_mass" in ring:
            base["mass"] = _num(ring["total_mass"], "[balls] total_mass") / count  # the double division
        per_ball = [dict(base) for _ in range(count)]
        overrides_tab = ring.get("override", [])
        if not isinstance(overrides_tab, list):
            raise InputError("[[balls.override]] must be an array of tables")
        for k, ov in enumerate(overrides_tab, 1):
            _warn_unknown(ov, BALL_TABLE_KEYS + ("ball",), f"[[balls.override]] {k}")
            idx = ov.get("ball")
            if isinstance(idx, bool) or not isinstance(idx, int) or not 1 <= idx <= count:
                raise InputError(f"[[balls.override]] {k}: 'ball' must be an integer 1..{count} (got {idx!r})")
            per_ball[idx - 1].update({key: ov[key] for key in BALL_TABLE_KEYS if key in ov})
        for i, t in enumerate(per_ball, 1):
            balls.append(_ball_from(t, {}, f"ball {i}", rolling))
    else:
        tabs = doc.get("ball", [])
        if not isinstance(tabs, list):
            raise InputError("[[ball]] must be an array of tables")
        for i, bt in enumerate(tabs, 1):
            _warn_unknown(bt, BALL_TABLE_KEYS, f"[[ball]] {i}")
            balls.append(_ball_from(bt, fr_defaults, f"ball {i}", rolling))
    kappa = fr.get("kappa")
    try:
        p = Params(_num(rotor["mass"], "rotor.mass"), _num(rotor["stiffness"], "rotor.stiffness"),
                   _num(rotor.get("damping", 0.0), "rotor.damping"), _num(rotor["unbalance"], "rotor.unbalance"),
                   _num(doc["speed"]["omega"], "speed.omega"), balls, law,
                   None if kappa is None else _num(kappa, "friction.kappa"), source=str(path))
    except KeyError as ex:
        raise InputError(f"missing key {ex}") from None
    for ov in overrides:
        apply_override(p, ov)
    p.check()
    return p


def apply_override(p, assignment):
    """NAME=VALUE with model.md symbols: omega U k c M_r kappa; m l r mu d mu_c mu_s v_s for
    every ball, or with a 1-based index (m3, l12, mu_c2) for one ball."""
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
    mt = BALL_SYMBOL_RE.match(name)
    if not mt:
        raise InputError(f"--set: unknown parameter {name!r}")
    base, idx = mt.group(1), (int(mt.group(2)) if mt.group(2) else None)
    if idx is not None and not 1 <= idx <= p.n:
        raise InputError(f"--set {name}: ball index out of range (the scene has {p.n} balls)")
    for i, b in enumerate(p.balls, 1):
        if idx is None or idx == i:
            setattr(b, base, v)


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
    """dF_i/dbdot_i at bdot_i = 0 (the exp factor of stribeck is 1 there, its slope 0)."""
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
# the model: A(beta) sdd = b(s, sdot), s = (q1, q2, beta_1..beta_n) (model.md §3, ball
# equations multiplied by l_i so that A is symmetric)
# ----------------------------------------------------------------------------------
def mass_matrix(p, betas):
    n = p.n
    A = mp.zeros(n + 2, n + 2)
    A[0, 0] = A[1, 1] = p.M()
    for i, be in enumerate(betas):
        ml = p.ml(i)
        A[0, 2 + i] = A[2 + i, 0] = -ml * mp.sin(be)
        A[1, 2 + i] = A[2 + i, 1] = ml * mp.cos(be)
        A[2 + i, 2 + i] = p.balls[i].j() * ml * mpf(p.balls[i].l)
    return A


def rhs(p, x):
    """b(s, sdot) for the full state x = (q1, q2, beta.., q1d, q2d, betad..)."""
    n = p.n
    q1, q2 = x[0], x[1]
    betas = x[2:2 + n]
    q1d, q2d = x[n + 2], x[n + 3]
    bds = x[n + 4:2 * n + 4]
    w = mpf(p.omega)
    M, k, c = p.M(), mpf(p.k), mpf(p.c)
    P1 = 2 * w * q2d + w * w * q1      # q1dd - a1 (a1: the rotor acceleration of §3)
    P2 = -2 * w * q1d + w * w * q2     # q2dd - a2
    r0 = M * P1 - c * (q1d - w * q2) - k * q1 + w * w * mpf(p.U)
    r1 = M * P2 - c * (q2d + w * q1) - k * q2
    rb = []
    for i in range(n):
        be, bd = betas[i], bds[i]
        ml = p.ml(i)
        sb, cb = mp.sin(be), mp.cos(be)
        r0 += ml * (bd + w) ** 2 * cb
        r1 += ml * (bd + w) ** 2 * sb
        rb.append(mpf(p.balls[i].l) * friction_force(p, i, bd) + ml * (-P1 * sb + P2 * cb))
    return [r0, r1] + rb


def vector_field(p, x):
    """f(x) = (sdot, A(beta)^-1 b(s, sdot))."""
    n = p.n
    A = mass_matrix(p, x[2:2 + n])
    sdd = mp.lu_solve(A, mp.matrix(rhs(p, x)))
    return list(x[n + 2:]) + [sdd[i] for i in range(n + 2)]


def db_ds_dsdot(p, s):
    """(db/ds, db/dsdot) at sdot = 0, derived by hand from rhs():
    rotor rows  b0 = M(w^2 q1 + 2w q2d) - c(q1d - w q2) - k q1 + w^2 U + sum ml (bd+w)^2 cos b,
                b1 = M(w^2 q2 - 2w q1d) - c(q2d + w q1) - k q2 +        sum ml (bd+w)^2 sin b;
    ball rows   l F(bd) + ml(-(w^2 q1 + 2w q2d) sin b + (w^2 q2 - 2w q1d) cos b)."""
    n = p.n
    q1, q2 = s[0], s[1]
    w = mpf(p.omega)
    w2 = w * w
    M, k, c = p.M(), mpf(p.k), mpf(p.c)
    Gs = mp.zeros(n + 2, n + 2)
    Gv = mp.zeros(n + 2, n + 2)
    Gs[0, 0] = Gs[1, 1] = M * w2 - k
    Gs[0, 1] = c * w
    Gs[1, 0] = -c * w
    Gv[0, 0] = Gv[1, 1] = -c
    Gv[0, 1] = 2 * w * M
    Gv[1, 0] = -2 * w * M
    for i in range(n):
        ml = p.ml(i)
        sb, cb = mp.sin(s[2 + i]), mp.cos(s[2 + i])
        # rotor rows: d/dbeta of ml w^2 (cos b, sin b); d/dbd of ml (bd + w)^2 (..) = 2 ml w (..)
        Gs[0, 2 + i] = -ml * w2 * sb
        Gs[1, 2 + i] = ml * w2 * cb
        Gv[0, 2 + i] = 2 * ml * w * cb
        Gv[1, 2 + i] = 2 * ml * w * sb
        # ball row i
        Gs[2 + i, 0] = -ml * w2 * sb
        Gs[2 + i, 1] = ml * w2 * cb
        Gs[2 + i, 2 + i] = -ml * w2 * (q1 * cb + q2 * sb)
        Gv[2 + i, 0] = -2 * w * ml * cb
        Gv[2 + i, 1] = -2 * w * ml * sb
        Gv[2 + i, 2 + i] = mpf(p.balls[i].l) * friction_slope0(p, i)
    return Gs, Gv


def _as_mp_state(p, s):
    return [v if isinstance(v, mpf) else mpf(v) for v in list(s)[:p.n + 2]]


def jacobian(p, s):
    """(2n+4)x(2n+4) J = [[0, I], [A^-1 db/ds, A^-1 db/dsdot]] at an equilibrium (model.md §6).
    s: (q1, q2, beta_1..beta_n) (a longer state must have zero velocities)."""
    n = p.n
    s = _as_mp_state(p, s)
    Gs, Gv = db_ds_dsdot(p, s)
    Ainv = mp.inverse(mass_matrix(p, s[2:]))
    P, Q = Ainv * Gs, Ainv * Gv
    m = n + 2
    J = mp.zeros(2 * m, 2 * m)
    for r in range(m):
        J[r, m + r] = 1
        for col in range(m):
            J[m + r, col] = P[r, col]
            J[m + r, m + col] = Q[r, col]
    return J


def state_scales(p, s):
    """Per-coordinate scales (q, beta, qdot, betadot) for finite differences and error norms."""
    n = p.n
    Q = p.displacement_scale() + mp.hypot(s[0], s[1])
    w = mpf(p.omega)
    return [Q, Q] + [mpf(1)] * n + [w * Q, w * Q] + [w] * n


def jacobian_fd(p, s, rel_step=None):
    """Central differences of the full vector_field() at x = (s, 0), one column per state
    coordinate, at mp.dps + 20 with step 10^(-dps/3) times the coordinate's scale: truncation
    ~10^(-2 dps/3), rounding ~10^(-dps-20+dps/3). Independent of db_ds_dsdot()."""
    dps = mp.dps
    s = _as_mp_state(p, s)
    with mp.extradps(20):
        x0 = list(s) + [mpf(0)] * (p.n + 2)
        sc = state_scales(p, s)
        h0 = mpf(10) ** (-(dps // 3)) if rel_step is None else mpf(rel_step)
        D = p.dim
        J = mp.zeros(D, D)
        for col in range(D):
            h = h0 * sc[col]
            xp, xm = list(x0), list(x0)
            xp[col] += h
            xm[col] -= h
            fp, fm = vector_field(p, xp), vector_field(p, xm)
            for row in range(D):
                J[row, col] = (fp[row] - fm[row]) / (2 * h)
    return J


def jacobian_mismatch(p, s, J=None, Jfd=None):
    """max over entries of |J - J_fd| in the state-scaled matrix, relative to that row's
    largest scaled entry (the entries span many orders and carry different units)."""
    J = jacobian(p, s) if J is None else J
    Jfd = jacobian_fd(p, s) if Jfd is None else Jfd
    sc = state_scales(p, _as_mp_state(p, s))
    worst = mpf(0)
    D = p.dim
    for r in range(D):
        rowmax = max(abs(J[r, k]) * sc[k] for k in range(D)) / sc[r]
        if rowmax == 0:
            continue
        for k in range(D):
            worst = max(worst, abs(J[r, k] - Jfd[r, k]) * sc[k] / sc[r] / rowmax)
    return worst


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


def eigenvalues(J, scales=None):
    """All eigenvalues (mp.eig at the current precision), sorted. J is real, so an imaginary
    part below rounding level (10^(10 - dps) max|lambda|) is set to exactly 0.

    scales: optional per-coordinate scales d; mp.eig then runs on the similar matrix
    D^-1 J D (same eigenvalues; better graded). mp's Hessenberg QR deflates only when a
    subdiagonal falls below eps/(100 n) of its diagonal neighbours, which the rounding of a
    stiff matrix (entries ~1e6 next to eigenvalues ~1e-4) occasionally never reaches
    (seen once in 15 rows of the n = 11 scene at 80 digits): then it is retried at 7 and 13
    more digits (the rounding pattern changes; the values are as exact as before)."""
    D = J.rows
    if scales is not None:
        Js = mp.zeros(D, D)
        for i in range(D):
            for j in range(D):
                Js[i, j] = J[i, j] * scales[j] / scales[i]
    else:
        Js = J
    raw = None
    for extra in (0, 7, 13):
        try:
            with mp.extradps(extra):
                raw = [mpc(z) for z in mp.eig(Js, left=False, right=False)]
            break
        except RuntimeError:
            continue
    if raw is None:
        raise RuntimeError("mp.eig: QR failed to converge at three precisions")
    raw = [mpc(+z.real, +z.imag) for z in raw]      # round back to the working precision
    # an imaginary part at rounding level of the whole spectrum is 0 (J is real): a real
    # eigenvalue of multiplicity 2 (equal balls) comes out as a pair with Im ~ eps max|lambda|
    tiny = mpf(10) ** (-(mp.dps - 10)) * max(abs(z) for z in raw)
    ev = [mpc(z.real, 0) if abs(z.imag) <= tiny else z for z in raw]
    return sort_eigenvalues(ev)


def trace(J):
    return sum(J[i, i] for i in range(J.rows))


# ----------------------------------------------------------------------------------
# static equations and their residual
# ----------------------------------------------------------------------------------
def wrap(a):
    t = 2 * mp.pi
    a = mp.fmod(a, t)
    if a < 0:
        a += t
    if a >= t:
        a -= t
    return a


def angdist(a, b):
    """Distance of two angles on the circle, in [0, pi]."""
    t = 2 * mp.pi
    d = abs(a - b)
    if d >= t:
        d = mp.fmod(d, t)
    return min(d, t - d)


def W_of(p, betas):
    """W(beta) = U + sum m_i l_i e^{i beta_i} (complex), docs/model.md §13."""
    return mpf(p.U) + sum(p.ml(i) * mp.expj(be) for i, be in enumerate(betas))


def q_of(p, betas):
    """q from the two linear rotor equations: (K + iC) q = w^2 W(beta)."""
    K, C = p.KC()
    w = mpf(p.omega)
    return w * w * W_of(p, betas) / mpc(K, C)


def static_residual(p, s):
    return rhs(p, list(s) + [mpf(0)] * (p.n + 2))


def residual_norm(p, s):
    """max over the n + 2 static equations of |b_i| / (the size of that equation's terms):
    rotor rows over w^2 (U + sum ml) + (k + w^2 M + c w)|q|, ball rows over m_i l_i w^2 (|q| + Q)."""
    q1, q2 = s[0], s[1]
    w2 = mpf(p.omega) ** 2
    qn = mp.hypot(q1, q2)
    Q = p.displacement_scale()
    scale_rotor = w2 * p.capacity() + (mpf(p.k) + w2 * p.M() + mpf(p.c) * mp.sqrt(w2)) * qn
    r = static_residual(p, s)
    out = max(abs(r[0]), abs(r[1])) / scale_rotor
    for i in range(p.n):
        out = max(out, abs(r[2 + i]) / (p.ml(i) * w2 * (qn + Q)))
    return out


def newton_static(p, s, extra_dps=20, maxit=40):
    """Newton on the n + 2 static equations b(s, 0) = 0 (Jacobian db/ds by hand) at
    mp.dps + extra_dps. Returns (s, converged); s unchanged if the Jacobian is singular."""
    target = mpf(10) ** (-(mp.dps + 5))
    with mp.extradps(extra_dps):
        s = [mpf(v) for v in s]
        Q = p.displacement_scale()
        for _ in range(maxit):
            Gs, _unused = db_ds_dsdot(p, s)
            try:
                ds = mp.lu_solve(Gs, -mp.matrix(static_residual(p, s)))
            except ZeroDivisionError:
                return s, False
            s = [s[i] + ds[i] for i in range(len(s))]
            qs = Q + mp.hypot(s[0], s[1])
            size = max([abs(ds[0]) / qs, abs(ds[1]) / qs] + [abs(ds[2 + i]) for i in range(p.n)])
            if size < target:
                return s, True
    return s, False


# ----------------------------------------------------------------------------------
# isolated equilibria, q != 0 (docs/model.md §13.2)
# ----------------------------------------------------------------------------------
class Aligned:
    """An isolated equilibrium: all balls on the line of q, e^{i beta_i} = sigma_i e^{i phi}."""

    def __init__(self, p, pattern, member, phi, S, flags=()):
        self.pattern = pattern          # '+'/'-' string, first char '+'
        self.member = member            # 1: phi = r - delta, 2: phi = pi - r - delta
        self.phi = wrap(phi)
        self.S = S
        self.flags = set(flags)
        opposite = wrap(phi + mp.pi)
        self.betas = [self.phi if ch == "+" else opposite for ch in pattern]
        q = (mpf(p.omega) ** 2) * (mpf(p.U) + S * mp.expj(phi)) / mpc(*p.KC())
        self.q1, self.q2 = q.real, q.imag

    @property
    def state(self):
        return [self.q1, self.q2] + list(self.betas)

    def family(self, n):
        if n == 2:
            return "together" if self.pattern == "++" else "opposite"
        return "aligned"

    def __repr__(self):
        return (f"Aligned({self.pattern} #{self.member} phi={mp.nstr(self.phi, 17)} "
                f"q=({mp.nstr(self.q1, 12)}, {mp.nstr(self.q2, 12)}) flags={sorted(self.flags)})")


def patterns(n):
    """All 2^(n-1) sign patterns with sigma_1 = '+' (sigma and -sigma are the same states)."""
    for code in range(2 ** (n - 1)):
        yield "+" + "".join("-" if (code >> (n - 2 - k)) & 1 else "+" for k in range(n - 1))


# near-degenerate flags: a double-precision program cannot decide these cases robustly
NEAR_FOLD_REL = mpf(10) ** -12   # 1 - |C S / R| below this: the two roots are ~1e-6 rad apart
NEAR_MERGE_REL = mpf(10) ** -12  # |U + S e^{i phi}| / (U + |S|) below this: q ~ 0 (on B)


def aligned_equilibria(p):
    """Every isolated equilibrium with q != 0, by sign pattern. Raises InputError for the
    degenerate U = 0, C = 0 case (each pattern with S != 0 gives a circle of equilibria)."""
    K, C = p.KC()
    U = mpf(p.U)
    n = p.n
    out = []
    if K == 0 and C == 0:
        return out                       # no bounded rotor state with q != 0
    if U == 0:
        if C == 0:
            raise InputError("U = 0 with c = 0: the aligned equilibria form circles "
                             "(rotational invariance); not covered by the n-ball reference")
        return out                       # C S = 0 needs S = 0, and then q = 0 (a point of B)
    R = U * mp.hypot(K, C)
    delta = mp.atan2(C * U, K * U)
    a = [p.ml(i) for i in range(n)]
    for pat in patterns(n):
        S = sum(a[i] if ch == "+" else -a[i] for i, ch in enumerate(pat))
        x = -C * S / R
        if abs(x) > 1:
            continue
        r = mp.asin(x)
        flags = set()
        if 1 - abs(x) < NEAR_FOLD_REL:
            flags.add("near_fold")
        roots = [(1, r - delta)] if abs(x) == 1 else [(1, r - delta), (2, mp.pi - r - delta)]
        for member, phi in roots:
            f = set(flags)
            if abs(x) == 1:
                f.add("double_root")
            if abs(U + S * mp.expj(phi)) < NEAR_MERGE_REL * (U + abs(S)):
                f.add("near_merge")
            out.append(Aligned(p, pat, member, phi, S, f))
    return out


def pattern_root_count(p):
    """{pattern: N_sigma} from the existence condition alone (cheap, every pattern)."""
    return {pat: sum(1 for e in aligned_equilibria(p) if e.pattern == pat) for pat in patterns(p.n)}


# ----------------------------------------------------------------------------------
# completeness check: multistart Newton on the static equations (n <= 4)
# ----------------------------------------------------------------------------------
# Grid: beta_i = 2 pi k_i / G + 0.1 i (i = 1..n, k_i = 0..G-1; the offsets keep the starts off
# the symmetric configurations), G = 64 for n = 2 (4096 starts), 16 for n = 3 (4096), 9 for
# n = 4 (6561; the grid sizes of docs/model.md §13.2). The equations solved are the static
# equations b(s, 0) = 0 with the two linear rotor rows solved exactly for q = w^2 W/(K + iC),
# and each ball row m_i l_i w^2 Im(e^{-i beta_i} q) = 0 divided by m_i l_i w^2 |q|:
#     g_i(beta) = Im(e^{-i beta_i} q(beta)) / |q(beta)|,   i = 1..n.
# For q != 0 this is equivalent to the static equations, and the division keeps the balanced
# continuum B (q = 0, where every g_i would vanish) from attracting the iteration. Nothing of
# the line argument of §13.2 is used. The search runs in double precision (a basin search);
# every converged point is then polished in mp on the full n + 2 static equations.
MULTISTART_GRID = {2: 64, 3: 16, 4: 9}


def _solve_float(Jm, rhs_):
    """Gaussian elimination with partial pivoting (small dense float systems)."""
    n = len(rhs_)
    a = [row[:] + [rhs_[i]] for i, row in enumerate(Jm)]
    for c in range(n):
        piv = max(range(c, n), key=lambda r: abs(a[r][c]))
        if abs(a[piv][c]) < 1e-300:
            return None
        a[c], a[piv] = a[piv], a[c]
        for r in range(c + 1, n):
            f = a[r][c] / a[c][c]
            if f:
                for k in range(c, n + 1):
                    a[r][k] -= f * a[c][k]
    x = [0.0] * n
    for r in range(n - 1, -1, -1):
        x[r] = (a[r][n] - sum(a[r][k] * x[k] for k in range(r + 1, n))) / a[r][r]
    return x


def _multistart_float(p, grid, maxit=50):
    import cmath
    import itertools
    n = p.n
    K, C = (float(v) for v in p.KC())
    z0 = float(p.omega) ** 2 / complex(K, C)
    a = [float(p.ml(i)) for i in range(n)]
    U = float(p.U)
    found = []
    for ks in itertools.product(range(grid), repeat=n):
        b = [2 * math.pi * k / grid + 0.1 * (i + 1) for i, k in enumerate(ks)]
        for _ in range(maxit):
            e = [cmath.exp(1j * v) for v in b]
            q = z0 * (U + sum(a[i] * e[i] for i in range(n)))
            qa = abs(q)
            if qa == 0:
                break
            u = q / qa
            g = [(u / e[i]).imag for i in range(n)]
            if max(abs(v) for v in g) < 1e-13:
                found.append([v % (2 * math.pi) for v in b])
                break
            # dq/dbeta_j = z0 i a_j e_j;  du = i u Im(conj(u) dq) / |q|
            du = [1j * u * (u.conjugate() * z0 * 1j * a[j] * e[j]).imag / qa for j in range(n)]
            Jm = [[(du[j] / e[i]).imag - ((u / e[i]).real if i == j else 0.0) for j in range(n)]
                  for i in range(n)]
            step = _solve_float(Jm, [-v for v in g])
            if step is None:
                break
            big = max(abs(v) for v in step)
            if big > 0.5:
                step = [v * 0.5 / big for v in step]
            b = [b[i] + step[i] for i in range(n)]
    # merge duplicates (max angle distance < 1e-6 rad)
    uniq = []
    for b in found:
        for u_ in uniq:
            if max(min(abs(x - y), 2 * math.pi - abs(x - y)) for x, y in zip(b, u_)) < 1e-6:
                break
        else:
            uniq.append(b)
    return uniq, len(found)


def multistart(p, grid=None):
    """Completeness check (n <= 4): roots found by the grid-started Newton, polished in mp,
    against aligned_equilibria(). Returns a dict with 'starts', 'converged', 'found',
    'missed' (pattern roots not found) and 'extra' (roots that are no pattern root)."""
    n = p.n
    grid = MULTISTART_GRID.get(n) if grid is None else grid
    if grid is None:
        raise ValueError(f"multistart is for n <= 4, got n = {n}")
    uniq, nconv = _multistart_float(p, grid)
    ref = aligned_equilibria(p)
    polished = []
    for b in uniq:
        betas = [mpf(v) for v in b]
        q = q_of(p, betas)
        s, ok = newton_static(p, [q.real, q.imag] + betas)
        s = [s[0], s[1]] + [wrap(v) for v in s[2:]]
        polished.append((s, ok))
    matched = set()
    extra = []
    tol = mpf(10) ** -20
    for s, ok in polished:
        hit = None
        for k, e in enumerate(ref):
            if max(angdist(x, y) for x, y in zip(s[2:], e.betas)) < tol:
                hit = k
                break
        if hit is None:
            extra.append((s, ok, residual_norm(p, s)))
        else:
            matched.add(hit)
    missed = [e for k, e in enumerate(ref) if k not in matched]
    return {"starts": grid ** n, "grid": grid, "converged": nconv, "found": len(uniq),
            "reference": len(ref), "missed": missed, "extra": extra}


# ----------------------------------------------------------------------------------
# the balanced set B (docs/model.md §13.4)
# ----------------------------------------------------------------------------------
def B_exists(p):
    """B is nonempty iff the lengths U, m_1 l_1, .., m_n l_n close a polygon:
    max(U, m_i l_i) <= (U + sum m_j l_j) / 2."""
    sides = [mpf(p.U)] + [p.ml(i) for i in range(p.n)]
    return 2 * max(sides) <= sum(sides)


def best_pair(p, betas):
    """The chart pair (a, b) maximising m_a l_a m_b l_b |sin(beta_a - beta_b)|."""
    best = None
    for a_ in range(p.n):
        for b_ in range(a_ + 1, p.n):
            v = p.ml(a_) * p.ml(b_) * abs(mp.sin(betas[a_] - betas[b_]))
            if best is None or v > best[0]:
                best = (v, a_, b_)
    return best[1], best[2]


def polish_onto_B(p, betas, extra_dps=20, maxit=60):
    """Newton on W(beta) = 0 (2 real equations) in the two angles of best_pair(), the others
    held. If that does not converge, or moves an angle by more than POLISH_MAX_SHIFT (near a
    collinear point of B, where the 2 x 2 chart Jacobian is singular), a minimum-norm
    Gauss-Newton on all n angles (pseudo-inverse of dW, rank 1 allowed) is used instead.
    Returns (betas wrapped to [0, 2 pi), converged)."""
    start = [mpf(v) for v in betas]
    target = mpf(10) ** (-(mp.dps + 5))
    with mp.extradps(extra_dps):
        be, ok = _polish_pair(p, start, target, maxit)
        if not ok or max(abs(x - y) for x, y in zip(be, start)) > POLISH_MAX_SHIFT:
            be, ok = _polish_min_norm(p, start, target, maxit)
    return [wrap(+v) for v in be], ok


POLISH_MAX_SHIFT = mpf(10) ** -6


def _polish_pair(p, betas, target, maxit):
    be = [mpf(v) for v in betas]
    a_, b_ = best_pair(p, be)
    for _ in range(maxit):
        Wc = W_of(p, be)
        # dW/dbeta_j = i m_j l_j e^{i beta_j}
        da = 1j * p.ml(a_) * mp.expj(be[a_])
        db = 1j * p.ml(b_) * mp.expj(be[b_])
        det = da.real * db.imag - db.real * da.imag
        if det == 0:
            return be, False
        x = (-Wc.real * db.imag + db.real * Wc.imag) / det
        y = (-da.real * Wc.imag + da.imag * Wc.real) / det
        be[a_] += x
        be[b_] += y
        if max(abs(x), abs(y)) < target:
            return be, True
    return be, False


def _polish_min_norm(p, betas, target, maxit):
    be = [mpf(v) for v in betas]
    n = p.n
    for _ in range(maxit):
        Wc = W_of(p, be)
        rows = [[-p.ml(j) * mp.sin(be[j]) for j in range(n)], [p.ml(j) * mp.cos(be[j]) for j in range(n)]]
        g11 = mp.fsum(x * x for x in rows[0])
        g22 = mp.fsum(x * x for x in rows[1])
        g12 = mp.fsum(x * y for x, y in zip(*rows))
        det = g11 * g22 - g12 * g12
        w = [Wc.real, Wc.imag]
        if det > mpf(10) ** (-(mp.dps // 2)) * (g11 + g22) ** 2:
            y = [(g22 * w[0] - g12 * w[1]) / det, (g11 * w[1] - g12 * w[0]) / det]
        else:                               # rank 1: G+ = v v^T / lam, (lam, v) its top eigenpair
            lam = (g11 + g22) / 2 + mp.sqrt(((g11 - g22) / 2) ** 2 + g12 ** 2)
            if g12 != 0:
                v = [g12, lam - g11]
            else:
                v = [mpf(1), mpf(0)] if g11 >= g22 else [mpf(0), mpf(1)]
            nv = mp.hypot(v[0], v[1])
            v = [v[0] / nv, v[1] / nv]
            c = (v[0] * w[0] + v[1] * w[1]) / lam
            y = [c * v[0], c * v[1]]
        step = [-(rows[0][j] * y[0] + rows[1][j] * y[1]) for j in range(n)]
        be = [x + d for x, d in zip(be, step)]
        if max(abs(d) for d in step) < target:
            return be, True
    return be, False


def dW_rank(p, betas, idx=None):
    """Rank of the 2 x |idx| matrix [m_j l_j (-sin beta_j, cos beta_j)], j in idx (all balls by
    default): 0 for no balls, 1 iff the balls are collinear (|sin(beta_i - beta_j)| <
    10^(-dps/2) for every pair), else 2."""
    idx = list(range(p.n)) if idx is None else list(idx)
    if not idx:
        return 0
    tol = mpf(10) ** (-(mp.dps // 2))
    for a_ in range(len(idx)):
        for b_ in range(a_ + 1, len(idx)):
            if abs(mp.sin(betas[idx[a_]] - betas[idx[b_]])) > tol:
                return 2
    return 1


def tangent_basis(p, betas):
    """Orthonormal basis V_T (columns in state space R^(2n+4)) of T_beta B, from the explicit
    vectors of docs/model.md §13.4 on the pair of best_pair(), then Gram-Schmidt."""
    n = p.n
    a_, b_ = best_pair(p, betas)
    others = [j for j in range(n) if j not in (a_, b_)]
    vecs = []
    for j in others:
        d = [mpf(0)] * n
        d[j] = mpf(1)
        d[a_] = -p.ml(j) * mp.sin(betas[j] - betas[b_]) / (p.ml(a_) * mp.sin(betas[a_] - betas[b_]))
        d[b_] = -p.ml(j) * mp.sin(betas[j] - betas[a_]) / (p.ml(b_) * mp.sin(betas[b_] - betas[a_]))
        v = [mpf(0)] * p.dim
        for k in range(n):
            v[2 + k] = d[k]
        vecs.append(v)
    return _gram_schmidt(vecs)


def _gram_schmidt(vecs, basis=()):
    out = [list(b) for b in basis]
    new = []
    for v in vecs:
        w = list(v)
        for _ in range(2):                 # twice is enough (Kahan)
            for u in out:
                c = mp.fsum(x * y for x, y in zip(w, u))
                w = [x - c * y for x, y in zip(w, u)]
        nrm = mp.sqrt(mp.fsum(x * x for x in w))
        if nrm > mpf(10) ** (-(mp.dps // 2)):
            w = [x / nrm for x in w]
            out.append(w)
            new.append(w)
    return new


def deflated_spectrum(p, betas, J=None):
    """eig(V_N^T J V_N), V_N the orthonormal complement of the tangent space (n + 6 values;
    with friction none n - 2 of them are zero). J V_T = 0 exactly at a point of B."""
    J = jacobian(p, [0, 0] + list(betas)) if J is None else J
    VT = tangent_basis(p, betas)
    D = p.dim
    unit = [[mpf(1) if k == i else mpf(0) for k in range(D)] for i in range(D)]
    VN = _gram_schmidt(unit, VT)
    m = len(VN)
    JV = [[mp.fsum(J[r, k] * VN[c][k] for k in range(D)) for r in range(D)] for c in range(m)]
    Nm = mp.zeros(m, m)
    for r in range(m):
        for c in range(m):
            Nm[r, c] = mp.fsum(VN[r][k] * JV[c][k] for k in range(D))
    tv = max((mp.sqrt(mp.fsum(mp.fsum(J[r, k] * v[k] for k in range(D)) ** 2 for r in range(D))))
             for v in VT) if VT else mpf(0)
    return eigenvalues(Nm), tv


def split_structural(ev):
    """(structural zeros, the rest) by |lambda| < ZERO_REL max|lambda|."""
    scale = max(abs(z) for z in ev)
    zeros = [z for z in ev if abs(z) < ZERO_REL * scale]
    rest = [z for z in ev if abs(z) >= ZERO_REL * scale]
    return zeros, rest


def sample_B(p, count, max_tries=20000):
    """Up to `count` deterministic points of B (docs/model.md §13.4 sampling chart: free
    angles from a Kronecker sequence, balls a, b = the two largest m l; both sheets), each
    polished with polish_onto_B. For n = 2: the two mirror points (one if they coincide),
    or for U = 0 a few points of the circle beta_2 = beta_1 + pi."""
    if not B_exists(p):
        return []
    n = p.n
    a = [p.ml(i) for i in range(n)]
    U = mpf(p.U)
    order = sorted(range(n), key=lambda i: -a[i])
    i1, i2 = order[0], order[1]
    free = sorted(order[2:])
    out = []

    def add(beta_free):
        Rc = U + sum(a[j] * mp.expj(bj) for j, bj in zip(free, beta_free))
        rho = abs(Rc)
        a1, a2 = a[i1], a[i2]
        if rho == 0 or rho < abs(a1 - a2) or rho > a1 + a2:
            return False
        th = mp.atan2(-Rc.imag, -Rc.real)
        g1 = mp.acos(max(-1, min(1, (a1 * a1 + rho * rho - a2 * a2) / (2 * a1 * rho))))
        g2 = mp.acos(max(-1, min(1, (a2 * a2 + rho * rho - a1 * a1) / (2 * a2 * rho))))
        for sgn in ((1, -1) if g1 != 0 or g2 != 0 else (1,)):
            be = [mpf(0)] * n
            for j, bj in zip(free, beta_free):
                be[j] = bj
            be[i1] = th - sgn * g1
            be[i2] = th + sgn * g2
            be, _ok = polish_onto_B(p, be)
            if all(max(angdist(x, y) for x, y in zip(be, o)) > mpf(10) ** -20 for o in out):
                out.append(be)
        return True

    if n == 2 and U == 0:
        for k in range(count):
            t = 2 * mp.pi * k / count
            out.append([wrap(t), wrap(t + mp.pi)])
        return out
    if n == 2:
        add([])
        return out
    alpha = [mp.frac(mp.sqrt(mpf(pr))) for pr in (2, 3, 5, 7, 11, 13, 17, 19, 23, 29)][:len(free)]
    best = None
    for t in range(1, max_tries + 1):
        bf = [2 * mp.pi * mp.frac(t * al) for al in alpha]
        add(bf)
        if len(out) >= count:
            break
        if not out:
            # keep the least-violating candidate for the shrinking-box search below
            Rc = abs(U + sum(a[j] * mp.expj(bj) for j, bj in zip(free, bf)))
            v = max(Rc - (a[i1] + a[i2]), abs(a[i1] - a[i2]) - Rc)
            if best is None or v < best[0]:
                best = (v, bf)
        if t == 2000 and not out:
            break
    if not out and best is not None:
        # near the edge of existence the accepted region is tiny: shrink a box around the
        # least-violating point (deterministic pattern search on the violation)
        v, bf = best
        h = mpf(1)
        for _ in range(400):
            improved = False
            for j in range(len(free)):
                for sgn in (1, -1):
                    trial = list(bf)
                    trial[j] += sgn * h
                    Rc = abs(U + sum(a[jj] * mp.expj(bj) for jj, bj in zip(free, trial)))
                    tv = max(Rc - (a[i1] + a[i2]), abs(a[i1] - a[i2]) - Rc)
                    if tv < v:
                        v, bf, improved = tv, trial, True
            if v <= 0:
                break
            if not improved:
                h /= 2
        if v <= 0:
            add(bf)
    return out[:count] if count else out


# ----------------------------------------------------------------------------------
# analysis of one state at a given precision
# ----------------------------------------------------------------------------------
class Result:
    """Everything the reference knows about one equilibrium (aligned or balanced)."""

    def __init__(self, kind, state):
        self.kind = kind              # 'aligned' or 'balanced'
        self.state = state            # [q1, q2, beta..] (mp)
        self.eig = None               # full spectrum, sorted
        self.zeros = []               # structural zeros (balanced)
        self.normal = None            # non-structural eigenvalues, sorted
        self.residual = None
        self.trace_err = None
        self.seconds = None
        self.deflated = None
        self.jacobian_err = None
        self.digits = None
        self.polish = None            # balanced: (converged, largest angle change)


def analyse(p, kind, state, dps=WORK_DPS, deflate=False, check_jacobian=False):
    """Spectrum at `state` at dps digits. kind 'balanced': the state is first polished onto B
    (its q is set to 0)."""
    t0 = time.time()
    with mp.workdps(dps):
        s = [mpf(v) for v in state]
        polish = None
        if kind == "balanced":
            betas, ok = polish_onto_B(p, s[2:])
            polish = (ok, max((angdist(x, y) for x, y in zip(betas, s[2:])), default=mpf(0)))
            s = [mpf(0), mpf(0)] + betas
        r = Result(kind, s)
        r.polish = polish
        J = jacobian(p, s)
        r.eig = eigenvalues(J, state_scales(p, s))
        tr = trace(J)
        r.trace_err = abs(mp.fsum(r.eig) - tr) / max(mp.fsum(abs(z) for z in r.eig), mpf(10) ** -300)
        r.residual = residual_norm(p, s)
        if kind == "balanced":
            r.zeros, r.normal = split_structural(r.eig)
            if deflate:
                r.deflated = deflated_spectrum(p, s[2:], J)
        else:
            r.zeros, r.normal = [], list(r.eig)
        if check_jacobian:
            r.jacobian_err = jacobian_mismatch(p, s, J)
    r.seconds = time.time() - t0
    return r


def abscissa_of(ev):
    return max(z.real for z in ev) if ev else None


def _bottleneck_pairing(ref, got, cost):
    """Permutation perm (got[perm[k]] pairs with ref[k]) minimising the largest cost
    (binary search on the threshold + augmenting-path bipartite matching)."""
    n = len(ref)
    cmat = [[cost(ref[i], got[j]) for j in range(n)] for i in range(n)]
    vals = sorted(set(v for row in cmat for v in row))

    def match(th):
        owner = [-1] * n

        def aug(i, seen):
            for j in range(n):
                if cmat[i][j] <= th and not seen[j]:
                    seen[j] = True
                    if owner[j] < 0 or aug(owner[j], seen):
                        owner[j] = i
                        return True
            return False
        for i in range(n):
            if not aug(i, [False] * n):
                return None
        perm = [0] * n
        for j, i in enumerate(owner):
            perm[i] = j
        return perm
    lo, hi = 0, len(vals) - 1
    best = match(vals[hi])
    while lo < hi:
        mid = (lo + hi) // 2
        m = match(vals[mid])
        if m is not None:
            best, hi = m, mid
        else:
            lo = mid + 1
    return best


def verify_digits(p, kind, state, lo):
    """Reruns analyse() at WORK_DPS + VERIFY_EXTRA_DPS; digits on which the spectra agree."""
    hi = analyse(p, kind, state, WORK_DPS + VERIFY_EXTRA_DPS)
    with mp.workdps(WORK_DPS + VERIFY_EXTRA_DPS):
        scale = max(abs(z) for z in hi.eig)
        if len(lo.normal) != len(hi.normal) or len(lo.zeros) != len(hi.zeros):
            return 0.0, hi
        cost = (lambda x, y: float(abs(x - y) / abs(x)))
        perm = _bottleneck_pairing(hi.normal, lo.normal, cost)
        d = max([abs(hi.normal[k] - lo.normal[perm[k]]) / abs(hi.normal[k]) for k in range(len(hi.normal))]
                + [abs(z) / scale for z in lo.zeros] + [mpf(0)])
        d = max(d, max(abs(x - y) for x, y in zip(lo.state[2:], hi.state[2:])))
    return (float(-mp.log10(d)) if d > 0 else float(WORK_DPS + VERIFY_EXTRA_DPS)), hi


# ----------------------------------------------------------------------------------
# CSV (the contract of `stability-scan equilibria SCENE --format csv`)
# ----------------------------------------------------------------------------------
def csv_header(n):
    cols = ["family", "pattern", "member", "q1", "q2"] + [f"beta{i}" for i in range(1, n + 1)]
    cols += ["residual", "spectral_abscissa", "stable", "n_structural_zero"]
    for k in range(1, 2 * n + 5):
        cols += [f"re{k}", f"im{k}"]
    return cols


def _f(x):
    return repr(float(x))


def csv_row(p, family, pattern, member, res):
    """One row from a Result (structural zeros printed as 0,0, in their sorted place)."""
    n = p.n
    ev = res.eig
    zeros = set(id(z) for z in res.zeros)
    ab = abscissa_of(res.normal)
    stable = int(ab is not None and ab < 0)
    row = [family, pattern, str(member), _f(res.state[0]), _f(res.state[1])]
    row += [_f(b) for b in res.state[2:]]
    row += [_f(res.residual), _f(ab if ab is not None else 0), str(stable), str(len(res.zeros))]
    for z in ev:
        if id(z) in zeros:
            row += ["0", "0"]
        else:
            row += [_f(z.real), _f(z.imag)]
    assert len(row) == len(csv_header(n))
    return row


def reference_rows(p, samples=4, max_rows=None):
    """Reference results for the CSV: every aligned equilibrium and `samples` points of B."""
    rows = []
    for e in aligned_equilibria(p):
        rows.append((e.family(p.n), e.pattern, e.member, "aligned", e.state))
    for k, be in enumerate(sample_B(p, samples), 1):
        rows.append(("balanced", "", k, "balanced", [mpf(0), mpf(0)] + be))
    if max_rows is not None:
        rows = rows[:max_rows]
    return rows


def write_csv(p, out, samples=4, results=None):
    w = csv.writer(out, lineterminator="\n")
    w.writerow(csv_header(p.n))
    for fam, pat, mem, kind, st in reference_rows(p, samples):
        res = analyse(p, kind, st) if results is None else results[(fam, pat, mem)]
        w.writerow(csv_row(p, fam, pat, mem, res))


# ----------------------------------------------------------------------------------
# comparison with the C++ program's CSV
# ----------------------------------------------------------------------------------
# Tolerances (eigenvalues use --rtol, default 1e-8):
#   q (aligned): |q - q_ref| <= Q_TOL ((U + sum m l)/M + |q_ref|). Closed forms in double give
#      ~1e-15; the conditioning in our scenes (C|S|/R within 1e-6 of a fold: 1/sqrt(2e-6) ~ 700;
#      W = U + S e^{i phi} cancelling to 1e-6 at the edge of existence) stays < 1e-12:
#      >= 100x headroom, while a wrong root or branch is O(1).
#   beta (aligned): |beta - beta_ref| (mod 2 pi) <= BETA_TOL rad (same conditioning argument:
#      rounding 1e-16 amplified by <= 1e3 near the fold).
#   balanced rows: |q| <= Q_TOL (U + sum m l)/M (q = 0 exactly in theory), and the state lies on
#      B: |W(beta)| <= W_TOL (U + sum m l). W at the printed doubles is exact to ~n eps of its
#      terms if the program solved W = 0 in double (n <= 12: ~3e-15), so 1e-12 is >= 300x
#      headroom, while a point off B by 1e-6 rad in one angle already gives ~1e-7.
# Eigenvalues: |lambda_k - ref_k| <= rtol |ref_k| each (sorted pairing, bottleneck-optimal
#   min-distance pairing as fallback). Structural zeros: the printed row must have exactly
#   n_structural_zero eigenvalues equal to 0,0 and that count must be the reference's (from
#   its own spectrum: |lambda| < 1e-30 max|lambda|); the other eigenvalues are paired with the
#   reference's normal spectrum.
# Stability: `stable` must equal (normal abscissa < 0) wherever the reference abscissa is
#   farther than rtol |lambda_ab| from 0 (else undecidable at the tolerance, not checked);
#   spectral_abscissa itself to rtol |lambda_ab|.
Q_TOL = 1e-10
BETA_TOL = 1e-9
W_TOL = 1e-12
RESIDUAL_WARN = 1e-10

# Seconds per row for analyse() (Jacobian + mp.eig at WORK_DPS), CPU time on the 2-core
# development machine with other builds running: measured 0.08 (n = 3), 0.06-0.10 (4),
# 0.14-0.22 (5), 0.62-0.92 (11), 0.84-1.15 (12) on the reference_n scenes. The model below
# is ~1.3x that. The default --max-rows spends ~EIG_BUDGET_SECONDS on eigenvalues, so that a
# compare (plus two 120-digit verification rows and the all-row state checks) stays < ~30 s.
def eig_seconds(n):
    return 0.06 + 6.2e-5 * (2 * n + 4) ** 3


EIG_BUDGET_SECONDS = 18.0


def default_max_rows(n):
    return max(4, int(EIG_BUDGET_SECONDS / eig_seconds(n)))


class CsvError(InputError):
    pass


def read_csv(path, n):
    with open(path, newline="") as fh:
        lines = [ln for ln in fh if ln.strip() and not ln.lstrip().startswith("#")]
    if not lines:
        raise CsvError(f"{path}: empty CSV (no header)")
    reader = csv.DictReader(lines)
    header = reader.fieldnames or []
    need = csv_header(n)
    missing = [c for c in need if c not in header]
    if missing:
        raise CsvError(f"{path}: CSV lacks columns {missing[:8]}{' ...' if len(missing) > 8 else ''}")
    if f"beta{n + 1}" in header or f"re{2 * n + 5}" in header:
        raise CsvError(f"{path}: CSV has columns for more than {n} balls (scene has n = {n})")
    rows = list(reader)
    for k, r in enumerate(rows, 1):
        if None in r or any(r[c] is None for c in need):
            raise CsvError(f"{path}: data row {k} has {'too many' if None in r else 'too few'} fields")
    return rows


def _select(indices, k):
    """k evenly spaced entries of `indices` (all if k >= len)."""
    N = len(indices)
    if k >= N:
        return list(indices)
    if k <= 0:
        return []
    if k == 1:
        return [indices[0]]
    return sorted(set(indices[round(i * (N - 1) / (k - 1))] for i in range(k)))


def choose_rows(groups, max_rows):
    """Deterministic subset: max_rows split evenly over the families (surplus of a small
    family goes to the others), evenly spaced rows within each family (in CSV order)."""
    fams = [f for f in groups if groups[f]]
    share = {f: 0 for f in fams}
    left = max_rows
    while left > 0 and any(share[f] < len(groups[f]) for f in fams):
        for f in fams:
            if left > 0 and share[f] < len(groups[f]):
                share[f] += 1
                left -= 1
    out = set()
    for f in fams:
        out.update(_select([k for k, _ in groups[f]], share[f]))
    return out


def _parse_row(r, n, where):
    vals = {}
    try:
        for key in ["q1", "q2"] + [f"beta{i}" for i in range(1, n + 1)] + \
                   ["residual", "spectral_abscissa"] + \
                   [f"{c}{k}" for k in range(1, 2 * n + 5) for c in ("re", "im")]:
            vals[key] = float(r[key])
        vals["stable"] = int(r["stable"])
        vals["n_structural_zero"] = int(r["n_structural_zero"])
    except ValueError as ex:
        raise CsvError(f"{where}: unreadable number: {ex}") from None
    return vals


class Compare:
    def __init__(self, p, rtol=1e-8, max_rows=None, out=sys.stdout, multistart_check=True, cache=None):
        self.p, self.rtol, self.out = p, rtol, out
        self.max_rows = default_max_rows(p.n) if max_rows is None else max_rows
        self.multistart_check = multistart_check
        self.ok = True
        self.cache = {} if cache is None else cache     # (kind, state key) -> Result
        self.eig_time = 0.0
        self.n_checked = 0
        self.verified_kinds = set()

    def say(self, s):
        print(s, file=self.out)

    def fail(self, s):
        self.ok = False
        self.say("FAIL " + s)

    # -------------------------------------------------------------- driver
    def run(self, csv_path):
        p, n = self.p, self.p.n
        t0 = time.time()
        self.say(f"# reference: {p.source}\n#   {p.describe()}")
        self.say(f"# rtol {self.rtol:g}; aligned state: q {Q_TOL:g} x (scale + |q|), beta {BETA_TOL:g} rad; "
                 f"balanced: |W| <= {W_TOL:g} x (U + sum m l); eigenvalues checked on <= {self.max_rows} rows")
        rows = read_csv(csv_path, n)
        aligned_fams = ("together", "opposite") if n == 2 else ("aligned",)
        groups = {"aligned": [], "balanced": []}
        parsed = {}
        for k, r in enumerate(rows, 1):
            fam = (r["family"] or "").strip()
            where = f"row {k} ({fam})"
            if fam not in aligned_fams + ("balanced",):
                self.fail(f"{where}: unknown family {fam!r} (expected {', '.join(aligned_fams + ('balanced',))})")
                continue
            try:
                vals = _parse_row(r, n, where)
            except CsvError as ex:
                self.fail(str(ex))
                continue
            bad = [key for key, v in vals.items() if isinstance(v, float) and not math.isfinite(v)]
            if bad:
                self.fail(f"{where}: non-finite {bad[:4]}")
                continue
            vals["family"] = fam
            vals["pattern"] = (r["pattern"] or "").strip()
            vals["member"] = (r["member"] or "").strip()
            parsed[k] = vals
            groups["balanced" if fam == "balanced" else "aligned"].append((k, vals))
        eig_rows = choose_rows(groups, self.max_rows)
        self.check_aligned(groups["aligned"], eig_rows)
        self.check_balanced(groups["balanced"], eig_rows)
        if self.multistart_check and n <= 4:
            self.check_completeness()
        self.say(f"# {len(rows)} rows; eigenvalues of {self.n_checked} checked ({self.eig_time:.1f} s of mp.eig); "
                 f"total {time.time() - t0:.1f} s")
        self.say("PASS" if self.ok else "FAIL")
        return self.ok

    # -------------------------------------------------------------- reference, cached
    def result(self, kind, state):
        key = (kind, tuple(float(v) for v in state))
        if key not in self.cache:
            r = analyse(self.p, kind, state)
            self.cache[key] = r
        r = self.cache[key]
        self.eig_time += r.seconds
        self.n_checked += 1
        return r

    # -------------------------------------------------------------- aligned rows
    def check_aligned(self, rows, eig_rows):
        p, n = self.p, self.p.n
        ref = aligned_equilibria(p)
        by_pat = {}
        for e in ref:
            by_pat.setdefault(e.pattern, []).append(e)
        csv_by_pat = {}
        for k, v in rows:
            pat = v["pattern"]
            if n == 2:
                implied = "++" if v["family"] == "together" else "+-"
                if pat and pat != implied:
                    self.fail(f"row {k} ({v['family']}): pattern {pat!r}, the family implies {implied!r}")
                    continue
                pat = implied
            if len(pat) != n or pat[0] != "+" or any(ch not in "+-" for ch in pat):
                self.fail(f"row {k} (aligned): bad pattern {pat!r} (n = {n} signs, first '+')")
                continue
            csv_by_pat.setdefault(pat, []).append((k, v))
        # counts: every isolated equilibrium and no other
        n_ref, n_csv = len(ref), sum(len(v) for v in csv_by_pat.values())
        count_bad = []
        for pat in sorted(set(by_pat) | set(csv_by_pat)):
            R, Cr = by_pat.get(pat, []), csv_by_pat.get(pat, [])
            if len(R) != len(Cr):
                soft = any(e.flags & {"near_fold", "near_merge"} for e in R) or \
                    self._near_degenerate_pattern(pat)
                count_bad.append((pat, len(Cr), len(R), soft))
        hard = [c for c in count_bad if not c[3]]
        for pat, nc, nr, soft in count_bad[:20]:
            msg = f"pattern {pat}: {nc} rows in the CSV, {nr} reference equilibria"
            if soft:
                self.say(f"WARN {msg} (near a fold or merge: a double program may see another count)")
            else:
                self.fail(msg)
        if len(count_bad) > 20:
            self.say(f"... {len(count_bad) - 20} more patterns with wrong counts")
        self.say(f"{'PASS' if not hard else 'FAIL'} aligned count: {n_csv} rows, {n_ref} reference equilibria "
                 f"over {2 ** (n - 1)} patterns")
        # pair within a pattern (<= 2 each): nearest state, then check the member label
        Qs = self.Qs = p.displacement_scale()
        worst_q = worst_b = 0.0
        nbad = 0
        for pat, Cr in csv_by_pat.items():
            R = by_pat.get(pat, [])

            def dist(e, v):
                # pairing only (the check is _check_aligned_state): in doubles, and on ball 1,
                # since every ball of a pattern root sits at phi or phi + pi
                dq = math.hypot(v["q1"] - float(e.q1), v["q2"] - float(e.q2)) / float(Qs + mp.hypot(e.q1, e.q2))
                d1 = abs(v["beta1"] - float(e.betas[0])) % (2 * math.pi)
                return dq + min(d1, 2 * math.pi - d1)
            pairs = []
            if len(R) >= 1 and len(Cr) >= 1:
                if len(R) == 2 and len(Cr) >= 2:
                    straight = dist(R[0], Cr[0][1]) + dist(R[1], Cr[1][1])
                    swapped = dist(R[1], Cr[0][1]) + dist(R[0], Cr[1][1])
                    order = [0, 1] if straight <= swapped else [1, 0]
                    pairs = [(R[order[0]], Cr[0]), (R[order[1]], Cr[1])]
                else:
                    for kk, v in Cr[:len(R)]:
                        pairs.append((min(R, key=lambda e: dist(e, v)), (kk, v)))
            for e, (k, v) in pairs:
                ok, dq, db = self._check_aligned_state(e, k, v)
                worst_q, worst_b = max(worst_q, dq), max(worst_b, db)
                if not ok:
                    nbad += 1
                if k in eig_rows:
                    self.check_spectrum(k, v, e.state, "aligned", f"row {k} aligned {pat} #{e.member}")
        if rows:
            self.say(f"{'PASS' if nbad == 0 else 'FAIL'} aligned states: worst dq/tol {worst_q:.1e}, "
                     f"dbeta {worst_b:.1e} rad over {len(rows)} rows")

    def _near_degenerate_pattern(self, pat):
        """No reference root but within NEAR_FOLD_REL of a fold (the program may find a double root)."""
        p = self.p
        K, C = p.KC()
        U = mpf(p.U)
        if U == 0:
            return False
        S = sum(p.ml(i) if ch == "+" else -p.ml(i) for i, ch in enumerate(pat))
        x = abs(C * S) / (U * mp.hypot(K, C))
        return abs(x - 1) < NEAR_FOLD_REL

    def _check_aligned_state(self, e, k, v):
        p, n = self.p, self.p.n
        Qs = self.Qs
        dq = mp.hypot(mpf(v["q1"]) - e.q1, mpf(v["q2"]) - e.q2)
        qtol = Q_TOL * (Qs + mp.hypot(e.q1, e.q2))
        db = max(angdist(mpf(v[f"beta{i + 1}"]), e.betas[i]) for i in range(n))
        ok = True
        if dq > qtol or db > BETA_TOL:
            ok = False
            self.fail(f"row {k} aligned {e.pattern} #{e.member}: STATE MISMATCH dq/tol {float(dq / qtol):.1e} "
                      f"dbeta {float(db):.1e}; ref q=({mp.nstr(e.q1, 17)}, {mp.nstr(e.q2, 17)}) "
                      f"phi={mp.nstr(e.phi, 17)}")
        if v["member"] != str(e.member):
            ok = False
            self.fail(f"row {k} aligned {e.pattern}: member {v['member']!r}, the reference numbers this root "
                      f"{e.member} (phi = {'r - delta' if e.member == 1 else 'pi - r - delta'})")
        if v["n_structural_zero"] != 0:
            ok = False
            self.fail(f"row {k} aligned {e.pattern} #{e.member}: n_structural_zero {v['n_structural_zero']}, "
                      f"an isolated equilibrium has 0")
        if v["residual"] > RESIDUAL_WARN:
            self.say(f"WARN row {k}: residual {v['residual']:.1e}")
        return ok, float(dq / qtol), float(db)

    # -------------------------------------------------------------- balanced rows
    def check_balanced(self, rows, eig_rows):
        p, n = self.p, self.p.n
        exists = B_exists(p)
        iso = None
        if n == 2 and mpf(p.U) != 0:
            iso = sample_B(p, 2)           # the mirror points (one at a merge)
        if not exists and rows:
            self.fail(f"{len(rows)} balanced rows, but B is empty (max(U, m_i l_i) > (U + sum m l)/2)")
        elif exists and not rows:
            self.fail("no balanced rows, but B is nonempty (the polygon inequality holds)")
        elif iso is not None and len(rows) != len(iso):
            self.fail(f"balanced: {len(rows)} rows, the two-ball balanced set has {len(iso)} points")
        else:
            self.say(f"PASS balanced count: {len(rows)} rows, B {'nonempty' if exists else 'empty'}"
                     + (f" ({len(iso)} isolated points)" if iso is not None else ""))
        if not rows:
            return
        members = [v["member"] for _, v in rows]
        if sorted(members, key=lambda s: int(s) if s.isdigit() else -1) != [str(i) for i in range(1, len(rows) + 1)]:
            self.say(f"WARN balanced member numbers are not 1..{len(rows)}")
        cap = p.capacity()
        Qs = p.displacement_scale()
        worst_w = 0.0
        nbad = 0
        used_iso = set()
        for k, v in rows:
            betas = [mpf(v[f"beta{i + 1}"]) for i in range(n)]
            w = abs(W_of(p, betas)) / cap
            qn = mp.hypot(mpf(v["q1"]), mpf(v["q2"]))
            worst_w = max(worst_w, float(w))
            bad = []
            if w > W_TOL:
                bad.append(f"|W|/(U + sum m l) = {float(w):.2e} > {W_TOL:g} (not on B)")
            if qn > Q_TOL * Qs:
                bad.append(f"|q| = {float(qn):.2e} m, q = 0 on B")
            if iso is not None:
                d = [max(angdist(x, y) for x, y in zip(betas, pt)) for pt in iso]
                j = min(range(len(iso)), key=lambda t: d[t])
                if d[j] > BETA_TOL or j in used_iso:
                    bad.append(f"not one of the two-ball balanced points (nearest {float(d[j]):.1e} rad)")
                used_iso.add(j)
            with mp.workdps(WORK_DPS):
                pol, _ok = polish_onto_B(p, betas)
                expect = p.structural_zero_count(pol)
            if v["n_structural_zero"] != expect:
                bad.append(f"n_structural_zero {v['n_structural_zero']}, expected {expect}")
            if bad:
                nbad += 1
                self.fail(f"row {k} balanced #{v['member']}: " + "; ".join(bad))
            if k in eig_rows:
                self.check_spectrum(k, v, [0, 0] + betas, "balanced", f"row {k} balanced #{v['member']}")
        self.say(f"{'PASS' if nbad == 0 else 'FAIL'} balanced states: worst |W|/(U + sum m l) {worst_w:.1e} "
                 f"over {len(rows)} rows")

    # -------------------------------------------------------------- spectra
    def check_spectrum(self, k, v, state, kind, label):
        p, n, rtol = self.p, self.p.n, self.rtol
        first = kind not in self.verified_kinds
        self.verified_kinds.add(kind)
        res = self.result(kind, state)
        notes = []
        ok = True
        got_all = [mpc(v[f"re{j}"], v[f"im{j}"]) for j in range(1, 2 * n + 5)]
        printed_zeros = [z for z in got_all if z.real == 0 and z.imag == 0]
        # the contract's order (real part descending): a warning only, pairing does not rely on it
        nonzero = [z for z in got_all if z != 0]
        big = max((abs(z) for z in nonzero), default=mpf(0))
        if any(a.real < b.real - mpf(10) ** -12 * big for a, b in zip(nonzero, nonzero[1:])):
            self.say(f"WARN {label}: eigenvalues not sorted by real part descending")
        nz = v["n_structural_zero"]
        if kind == "balanced":
            if not res.polish[0] or res.polish[1] > BETA_TOL:
                self.say(f"WARN REFERENCE {label}: polishing onto B {'did not converge' if not res.polish[0] else ''}"
                         f" moved the angles by {mp.nstr(res.polish[1], 2)} rad")
            with mp.workdps(WORK_DPS):
                formula = p.structural_zero_count(res.state[2:])
            if formula != len(res.zeros):
                self.say(f"WARN REFERENCE {label}: {len(res.zeros)} zeros in the spectrum, "
                         f"{formula} by the tangent-space count")
            if len(res.zeros) != nz:
                ok = False
                notes.append(f"n_structural_zero {nz}, the reference spectrum has {len(res.zeros)} "
                             f"(|lambda| < 1e-30 max|lambda|)")
            if len(printed_zeros) < nz:
                ok = False
                notes.append(f"only {len(printed_zeros)} eigenvalues printed as exactly 0,0 for "
                             f"n_structural_zero = {nz}")
        # drop nz printed exact zeros; pair the rest with the normal spectrum
        got = list(got_all)
        for _ in range(min(nz, len(printed_zeros))):
            got.remove(mpc(0, 0))
        # both sides sorted alike: real parts within 1e-15 max|lambda| count as equal (the
        # program's doubles cannot order them more finely), then imaginary part descending
        refl = sort_eigenvalues(res.normal, rel=1e-15) if res.normal else []
        if len(got) != len(refl):
            ok = False
            notes.append(f"{len(got)} non-structural eigenvalues printed, the reference has {len(refl)}")
        else:
            got = sort_eigenvalues(got, rel=1e-15)
            scale = max(abs(z) for z in res.eig)

            def cost(y, x):               # y: reference, x: program
                return float(abs(x - y) / abs(y)) if abs(y) > 0 else float(abs(x) / scale)
            er = [cost(y, x) for x, y in zip(got, refl)]
            how = "sorted"
            if max(er, default=0) > rtol:
                perm = _bottleneck_pairing(refl, got, cost)
                got2 = [got[perm[j]] for j in range(len(refl))]
                er2 = [cost(y, x) for x, y in zip(got2, refl)]
                if max(er2) < max(er):
                    got, er, how = got2, er2, "min-distance"
            worst = max(er, default=0.0)
            notes.append(f"eig worst rel {worst:.1e} ({how} pairing)")
            for j, e_ in enumerate(er):
                if e_ > rtol:
                    ok = False
                    notes.append(f"EIG {j + 1}: got {mp.nstr(got[j], 17)} ref {mp.nstr(refl[j], 17)} (rel {e_:.1e})")
        # abscissa and stability (over the non-structural eigenvalues)
        if refl:
            ab = abscissa_of(refl)
            lam_ab = max(abs(z) for z in refl if z.real >= ab - rtol * abs(z))
            atol = rtol * lam_ab
            if abs(mpf(v["spectral_abscissa"]) - ab) > atol:
                ok = False
                notes.append(f"ABSCISSA got {v['spectral_abscissa']!r} ref {mp.nstr(ab, 17)}")
            if abs(ab) <= atol:
                notes.append("stability undecidable at rtol (abscissa ~ 0): not checked")
            elif v["stable"] != int(ab < 0):
                ok = False
                notes.append(f"STABLE got {v['stable']} ref {int(ab < 0)} (abscissa {mp.nstr(ab, 6)})")
        if first:
            digits, hi = verify_digits(p, kind, state, res)
            notes.append(f"reference verified to {digits:.0f} digits at {WORK_DPS + VERIFY_EXTRA_DPS}")
            if digits < 20:
                ok = False
                notes.append("REFERENCE: 80 vs 120 digits disagree")
            with mp.workdps(WORK_DPS):
                jerr = jacobian_mismatch(p, res.state)
            notes.append(f"J vs finite differences {mp.nstr(jerr, 2)}")
            if jerr > mpf(10) ** -25:     # truncation (kappa h)^2 ~ 1e-34 at kappa = 1e6
                ok = False
                notes.append("REFERENCE: hand-derived J differs from the vector field's derivative")
            if kind == "balanced":
                with mp.workdps(WORK_DPS):
                    dfl, tv = deflated_spectrum(p, res.state[2:])
                    dz, dn = split_structural(dfl)
                    agree = len(dn) == len(res.normal) and all(
                        abs(x - y) <= mpf(10) ** -40 * abs(y) for x, y in zip(dn, res.normal))
                notes.append(f"deflated spectrum {'agrees' if agree else 'DISAGREES'} (|J V_T| {mp.nstr(tv, 2)})")
                if not agree:
                    ok = False
        if not ok:
            self.ok = False
        self.say(f"{'PASS' if ok else 'FAIL'} {label}: " + "; ".join(notes))

    # -------------------------------------------------------------- reference completeness
    def check_completeness(self):
        t0 = time.time()
        ms = multistart(self.p)
        msg = (f"multistart Newton ({ms['grid']}^{self.p.n} = {ms['starts']} starts, {ms['converged']} converged, "
               f"{ms['found']} distinct) vs sign patterns ({ms['reference']}): ")
        if ms["extra"]:
            self.fail("REFERENCE " + msg + f"{len(ms['extra'])} roots that are no pattern root, e.g. "
                      f"{[mp.nstr(x, 10) for x in ms['extra'][0][0]]}")
        elif ms["missed"]:
            self.say("WARN " + msg + f"{len(ms['missed'])} pattern roots not reached from the grid "
                     f"({', '.join(f'{e.pattern}#{e.member}' for e in ms['missed'][:8])})")
        else:
            self.say("PASS " + msg + f"the same set ({time.time() - t0:.1f} s)")


def compare(csv_path, p, rtol=1e-8, max_rows=None, out=sys.stdout, multistart_check=True, cache=None):
    return Compare(p, rtol, max_rows, out, multistart_check, cache).run(csv_path)


# ----------------------------------------------------------------------------------
# CLI
# ----------------------------------------------------------------------------------
def print_reference(p, digits=20, max_rows=None, samples=4, out=sys.stdout):
    n = p.n
    K, C = p.KC()
    print(f"# {p.source}\n#   {p.describe()}", file=out)
    print(f"# working precision {WORK_DPS} digits; K = {mp.nstr(K, 17)}, C = {mp.nstr(C, 17)}; "
          f"B {'nonempty' if B_exists(p) else 'empty'}", file=out)
    eqs = aligned_equilibria(p)
    print(f"# {len(eqs)} isolated equilibria over {2 ** (n - 1)} sign patterns", file=out)
    if n <= 4:
        ms = multistart(p)
        print(f"# multistart check: {ms['starts']} starts, {ms['found']} distinct roots, "
              f"{len(ms['missed'])} missed, {len(ms['extra'])} extra", file=out)
    pts = sample_B(p, samples)
    items = [(e.family(n), e.pattern, e.member, "aligned", e.state, e.flags) for e in eqs]
    items += [("balanced", "", k, "balanced", [mpf(0), mpf(0)] + b, set()) for k, b in enumerate(pts, 1)]
    limit = default_max_rows(n) if max_rows is None else max_rows
    for idx, (fam, pat, mem, kind, st, flags) in enumerate(items, 1):
        head = f"\n[{idx}] {fam} {pat} #{mem}" + (f" flags={','.join(sorted(flags))}" if flags else "")
        print(head, file=out)
        print(f"  q = ({mp.nstr(st[0], digits)}, {mp.nstr(st[1], digits)})", file=out)
        print("  beta = " + ", ".join(mp.nstr(b, digits) for b in st[2:]), file=out)
        if idx > limit:
            continue
        r = analyse(p, kind, st, check_jacobian=(idx == 1))
        dg, _hi = verify_digits(p, kind, st, r) if idx <= 2 else (None, None)
        ab = abscissa_of(r.normal)
        print(f"  residual {mp.nstr(r.residual, 3)}, trace check {mp.nstr(r.trace_err, 3)}, "
              f"{len(r.zeros)} structural zeros, eig {r.seconds:.2f} s"
              + (f", verified digits {dg:.0f}" if dg is not None else "")
              + (f", |J - J_fd| {mp.nstr(r.jacobian_err, 3)}" if r.jacobian_err is not None else ""), file=out)
        print(f"  spectral abscissa (normal) = {mp.nstr(ab, digits)} "
              f"({'stable' if ab < 0 else 'not stable'})", file=out)
        for k, z in enumerate(r.eig, 1):
            tag = "  (structural 0)" if any(z is y for y in r.zeros) else ""
            print(f"  lambda{k} = {mp.nstr(z.real, digits):>{digits + 8}} {'+' if z.imag >= 0 else '-'} "
                  f"{mp.nstr(abs(z.imag), digits)} i{tag}", file=out)
    if len(items) > limit:
        print(f"\n# eigenvalues shown for the first {limit} of {len(items)} (--max-rows)", file=out)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                    help="override: omega U k c M_r kappa, m l r mu d mu_c mu_s v_s (all balls) or m3 l2 .. (one)")
    ap.add_argument("--compare", metavar="CSV", help="check the C++ program's equilibria CSV")
    ap.add_argument("--rtol", type=float, default=1e-8, help="eigenvalue relative tolerance (compare mode)")
    ap.add_argument("--max-rows", type=int, default=None,
                    help="rows whose eigenvalues are computed (default by n: ~20 s of mp.eig)")
    ap.add_argument("--no-multistart", action="store_true", help="skip the n <= 4 completeness check")
    ap.add_argument("--samples", type=int, default=4, help="points of B in reference / --csv mode")
    ap.add_argument("--csv", action="store_true", help="print the reference rows in the CSV contract")
    ap.add_argument("--digits", type=int, default=20, help="digits printed (reference mode)")
    a = ap.parse_args(argv)
    try:
        p = load_scene(a.scene, a.set)
        if a.compare:
            return 0 if compare(a.compare, p, a.rtol, a.max_rows, multistart_check=not a.no_multistart) else 1
        if a.csv:
            write_csv(p, sys.stdout, a.samples)
            return 0
        print_reference(p, a.digits, a.max_rows, a.samples)
        return 0
    except (InputError, OSError, tomllib.TOMLDecodeError) as ex:
        print(f"mp_reference_n: error: {type(ex).__name__}: {ex}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
