#!/usr/bin/env python3
"""Symbolic checks of docs/model.md §12 (LuGre friction) with sympy.

1. (12.7), (12.8): the bristle rate's derivatives, on each side of v = 0 (|v| = +-v),
   against sympy's differentiation of (12.2) with g of (12.1).
2. (12.9): the one-sided limits at v = 0 are 1 -+ sigma0 z / mu_s, and with sigma0 z = -tau
   they are 1 +- tau / mu_s; they differ unless z = 0.
3. §12.1 steady sliding: z = sgn(v) g / sigma0 makes z' = 0 and F = -N (g sgn v + sigma2 v).
4. §12.1 invariance: on |z| = mu_s / sigma0, z z' <= 0 for every v when mu_c <= mu_s.
5. (12.5): the ball row of (3.9) at rest with F of (12.3) gives sigma0 z = -tau.
6. (12.10): for n = 2, with A, D, E exact random rationals (A symmetric positive definite)
   and the LuGre blocks of (12.6) at rest, det(lambda I - J_c) det A = lambda^n det T_c(lambda)
   as polynomials in lambda, exactly.
7. The full (3n + 4) field of §12.2 for n = 2 derived symbolically (A(beta), b from (3.8),
   (3.9)), its Jacobian by sympy at an equilibrium with z != 0, one-sided in v: the block
   structure of (12.6) at rest (zero dz'/dz, dz'/dv = c+-, db/dz = -l N (sigma0), dD = l N
   (sigma1 c + sigma2)) checked entry by entry at a rational point.
Exit 0 if all hold, 1 otherwise. (/usr/bin/python3 with python3-sympy.)
"""
import random
import sys

import sympy as sp

fails = []


def check(name, cond):
    print(("ok   " if cond else "FAIL ") + name)
    if not cond:
        fails.append(name)


v, z = sp.symbols("v z", real=True)
s0, s1, s2, mc, ms, vs, N, l, tau = sp.symbols("sigma0 sigma1 sigma2 mu_c mu_s v_s N l tau", positive=True)
g = mc + (ms - mc) * sp.exp(-(v / vs) ** 2)                                   # (12.1)
gp = sp.diff(g, v)

# 1. derivatives on each side: |v| = sign * v
for sign in (1, -1):
    zdot = v - s0 * (sign * v) * z / g                                        # (12.2) with |v| = sign v
    dv_doc = 1 - s0 * z * (sign * g - (sign * v) * gp) / g ** 2               # (12.7)
    dz_doc = -s0 * (sign * v) / g                                             # (12.8)
    check(f"(12.7) dz'/dv, side {sign:+d}", sp.simplify(sp.diff(zdot, v) - dv_doc) == 0)
    check(f"(12.8) dz'/dz, side {sign:+d}", sp.simplify(sp.diff(zdot, z) - dz_doc) == 0)
    # 2. one-sided limit at 0
    lim = sp.limit(sp.diff(zdot, v), v, 0, "+" if sign > 0 else "-")
    check(f"(12.9) c at v -> 0{'+' if sign > 0 else '-'} = 1 - sign sigma0 z / mu_s",
          sp.simplify(lim - (1 - sign * s0 * z / ms)) == 0)
    check(f"(12.9) with sigma0 z = -tau: 1 {'+' if sign > 0 else '-'} tau/mu_s",
          sp.simplify(lim.subs(z, -tau / s0) - (1 + sign * tau / ms)) == 0)
    # 3. steady sliding on this side (v of sign `sign`)
    zss = sign * g / s0
    check(f"steady sliding z' = 0, side {sign:+d}", sp.simplify(zdot.subs(z, zss)) == 0)
    F = -N * (s0 * zss + s1 * zdot.subs(z, zss) + s2 * v)
    check(f"steady sliding F = -N (g sgn v + sigma2 v), side {sign:+d}", sp.simplify(F + N * (sign * g + s2 * v)) == 0)

# 4. invariance: on z = zb = +-mu_s/sigma0 and any v = sign |v|,
#    z z' = |v| (mu_s/sigma0) (sign sgn(zb) - mu_s/g) <= |v| (mu_s/sigma0) (1 - mu_s/g), and
#    mu_s - g = (mu_s - mu_c)(1 - exp(-(v/v_s)^2)) >= 0 when mu_c <= mu_s, so z z' <= 0.
av = sp.symbols("a", nonnegative=True)  # |v|
check("invariance: mu_s - g = (mu_s - mu_c)(1 - exp(-(v/v_s)^2)) (>= 0 for mu_c <= mu_s)",
      sp.simplify(ms - g - (ms - mc) * (1 - sp.exp(-(v / vs) ** 2))) == 0)
for zsign in (1, -1):
    for sign in (1, -1):
        zb = zsign * ms / s0
        gs = g.subs(v, sign * av)
        zzdot = zb * (sign * av - s0 * av * zb / gs)
        check(f"invariance: z z' = |v| mu_s/sigma0 (sgn(v) sgn(z) - mu_s/g) (z sign {zsign:+d}, v sign {sign:+d})",
              sp.simplify(zzdot - av * ms / s0 * (sign * zsign - ms / gs)) == 0)

# 5. equilibrium relation from the ball row at rest: 0 = l F - m l omega^2 tau l  (a_i = m l)
m, w, q1, q2, be = sp.symbols("m omega q1 q2 beta", real=True)
Nn = m * l * w ** 2
Frest = -Nn * s0 * z                                                          # (12.3) at v = 0
row = l * Frest + m * l * ((-w ** 2 * q1) * sp.sin(be) - (-w ** 2 * q2) * sp.cos(be))   # (3.9) b_{2+i} at rest
zsol = sp.solve(sp.Eq(row, 0), z)[0]
check("(12.5) sigma0 z = -(q1 sin beta - q2 cos beta)/l",
      sp.simplify(s0 * zsol + (q1 * sp.sin(be) - q2 * sp.cos(be)) / l) == 0)

# 6. (12.10) exactly, n = 2 balls: dimension d = 4, state 3n + 4 = 10
random.seed(12)
n, d = 2, 4
lam = sp.symbols("lambda")


def rational():
    return sp.Rational(random.randint(-40, 40), random.randint(1, 9))


Bm = sp.Matrix(d, d, lambda i, j: rational())
A = Bm * Bm.T + sp.eye(d)                                                     # symmetric positive definite
D = sp.Matrix(d, d, lambda i, j: rational())
E = sp.Matrix(d, d, lambda i, j: rational())
lN = [sp.Rational(random.randint(1, 30), 7) for _ in range(n)]               # l_i N_i
c = [sp.Rational(random.randint(1, 19), 10) for _ in range(n)]               # c_i (one side)
sig = [sp.Rational(3, 2), sp.Rational(1, 5), sp.Rational(1, 50)]             # sigma0, sigma1, sigma2
Dl = D.copy()
for i in range(n):
    Dl[2 + i, 2 + i] += lN[i] * (sig[1] * c[i] + sig[2])                      # (12.6): D += l N (sigma1 c + sigma2)
Bz = sp.zeros(d, n)
for i in range(n):
    Bz[2 + i, i] = -lN[i] * sig[0]                                            # dz'/dz = 0 at rest
Ainv = A.inv()
J = sp.zeros(2 * d + n, 2 * d + n)
J[0:d, d:2 * d] = sp.eye(d)
J[d:2 * d, 0:d] = -Ainv * E
J[d:2 * d, d:2 * d] = -Ainv * Dl
J[d:2 * d, 2 * d:] = Ainv * Bz
for i in range(n):
    J[2 * d + i, d + 2 + i] = c[i]
Ec = E.copy()
for i in range(n):
    Ec[2 + i, 2 + i] += lN[i] * sig[0] * c[i]                                 # spring sigma0 c
Tc = lam ** 2 * A + lam * Dl + Ec
lhs = sp.expand((lam * sp.eye(2 * d + n) - J).det(method="berkowitz") * A.det())
rhs = sp.expand(lam ** n * Tc.det(method="berkowitz"))
check("(12.10) det(lambda - J_c) det A = lambda^n det T_c(lambda), exactly (n = 2)", sp.expand(lhs - rhs) == 0)
# the left null vectors w_i = z_i - c_i beta_i
for i in range(n):
    L = sp.zeros(1, 2 * d + n)
    L[0, 2 * d + i] = 1
    L[0, 2 + i] = -c[i]
    check(f"w_{i + 1} = z_{i + 1} - c_{i + 1} beta_{i + 1} is a left null vector of J_c", (L * J) == sp.zeros(1, 2 * d + n))

# 7. the full field for n = 2, symbolic, Jacobian at a stuck state, each side
Mr, k, cd, U = sp.Rational(23, 200), sp.Integer(7100), sp.Rational(8, 5), sp.Rational(53, 10 ** 8)
ms_ = [sp.Rational(34, 10 ** 6), sp.Rational(29, 10 ** 6)]
ls_ = [sp.Rational(175, 10 ** 4), sp.Rational(182, 10 ** 4)]
js_ = [sp.Rational(7, 5), sp.Integer(1)]
P = dict(s0=[sp.Integer(180), sp.Integer(240)], s1=[sp.Rational(41, 1000)] * 2, s2=[sp.Rational(15, 10 ** 5)] * 2,
         mc=[sp.Rational(18, 10 ** 4)] * 2, ms=[sp.Rational(39, 10 ** 4), sp.Rational(47, 10 ** 4)],
         vs=[sp.Rational(45, 100)] * 2)
wv = sp.Integer(820)
X = sp.symbols("q1 q2 b1 b2 q1d q2d b1d b2d z1 z2", real=True)
Mt = Mr + sum(ms_)
Amat = sp.Matrix([[Mt, 0, -ms_[0] * ls_[0] * sp.sin(X[2]), -ms_[1] * ls_[1] * sp.sin(X[3])],
                  [0, Mt, ms_[0] * ls_[0] * sp.cos(X[2]), ms_[1] * ls_[1] * sp.cos(X[3])],
                  [-ms_[0] * ls_[0] * sp.sin(X[2]), ms_[0] * ls_[0] * sp.cos(X[2]), js_[0] * ms_[0] * ls_[0] ** 2, 0],
                  [-ms_[1] * ls_[1] * sp.sin(X[3]), ms_[1] * ls_[1] * sp.cos(X[3]), 0, js_[1] * ms_[1] * ls_[1] ** 2]])


def forces(side):
    """b of (3.9) with F of (12.3); |v| written as side * v (valid on that side of 0)."""
    out, zd = [], []
    for i in range(2):
        vv, zz = X[6 + i], X[8 + i]
        gi = P["mc"][i] + (P["ms"][i] - P["mc"][i]) * sp.exp(-(vv / P["vs"][i]) ** 2)
        zdi = vv - P["s0"][i] * side * vv * zz / gi
        Ni = ms_[i] * ls_[i] * wv ** 2
        out.append(-Ni * (P["s0"][i] * zz + P["s1"][i] * zdi + P["s2"][i] * vv))
        zd.append(zdi)
    P1 = 2 * wv * X[5] + wv ** 2 * X[0]
    P2 = -2 * wv * X[4] + wv ** 2 * X[1]
    b0 = Mt * P1 - cd * (X[4] - wv * X[1]) - k * X[0] + wv ** 2 * U
    b1 = Mt * P2 - cd * (X[5] + wv * X[0]) - k * X[1]
    bb = []
    for i in range(2):
        a = ms_[i] * ls_[i]
        b0 += a * (X[6 + i] + wv) ** 2 * sp.cos(X[2 + i])
        b1 += a * (X[6 + i] + wv) ** 2 * sp.sin(X[2 + i])
        bb.append(ls_[i] * out[i] + a * (-P1 * sp.sin(X[2 + i]) + P2 * sp.cos(X[2 + i])))
    return sp.Matrix([b0, b1] + bb), zd


betas = [sp.Rational(1), sp.Rational(22, 10)]
Kd, Cd = k - wv ** 2 * Mt, cd * wv
W = U + sum(ms_[i] * ls_[i] * sp.exp(sp.I * betas[i]) for i in range(2))
qc = wv ** 2 * W / (Kd + sp.I * Cd)
q1v, q2v = sp.re(sp.expand_complex(qc)), sp.im(sp.expand_complex(qc))
taus = [(q1v * sp.sin(betas[i]) - q2v * sp.cos(betas[i])) / ls_[i] for i in range(2)]
point = {X[0]: q1v, X[1]: q2v, X[2]: betas[0], X[3]: betas[1], X[4]: 0, X[5]: 0, X[6]: 0, X[7]: 0,
         X[8]: -taus[0] / P["s0"][0], X[9]: -taus[1] / P["s0"][1]}
# At the equilibrium s'' = 0, so the s'' rows of J are A^-1 db/dx (the (dA/dx) s'' term of
# (6.5) vanishes): checking db/dx and the z' rows checks (12.6) at rest.
for side in (1, -1):
    b, zd = forces(side)
    bn = b.subs(point).evalf(40)
    zn = [e.subs(point).evalf(40) for e in zd]
    scale_b = max(abs(sp.N(ms_[i] * ls_[i] * wv ** 2 * ls_[i] * P["ms"][i], 40)) for i in range(2))
    check(f"b(s, 0, z) = 0 and z' = 0 at the stuck state (12.5), side {side:+d}",
          max(abs(e) for e in bn) < 1e-30 * scale_b * 1e3 and max(abs(e) for e in zn) == 0)
    Jb = b.jacobian(sp.Matrix(X)).subs(point).evalf(40)
    Jz = sp.Matrix(zd).jacobian(sp.Matrix(X)).subs(point).evalf(40)
    for i in range(2):
        Ni = ms_[i] * ls_[i] * wv ** 2
        ci = 1 + side * taus[i] / P["ms"][i]                                  # (12.9)
        check(f"side {side:+d}, ball {i + 1}: dz'/dv = c = 1 +- tau/mu_s (12.9)", abs(Jz[i, 6 + i] - sp.N(ci, 40)) < 1e-30)
        check(f"side {side:+d}, ball {i + 1}: dz'/dz = 0 and no other z' entry (12.8)",
              max(abs(Jz[i, k]) for k in range(10) if k != 6 + i) < 1e-30)
        want = sp.N(-ls_[i] * Ni * P["s0"][i], 40)
        check(f"side {side:+d}, ball {i + 1}: db/dz = -l N sigma0 in row 2+i only (12.6)",
              abs(Jb[2 + i, 8 + i] - want) < 1e-30 * abs(want)
              and max(abs(Jb[r, 8 + i]) for r in range(4) if r != 2 + i) == 0)
        fr = sp.N(-ls_[i] * Ni * (P["s1"][i] * ci + P["s2"][i]), 40)
        check(f"side {side:+d}, ball {i + 1}: db_(2+i)/dv_i = -l N (sigma1 c + sigma2) (12.6)",
              abs(Jb[2 + i, 6 + i] - fr) < 1e-30 * abs(fr))

print("PASS" if not fails else f"FAIL: {len(fails)} checks")
sys.exit(1 if fails else 0)
