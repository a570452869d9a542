#!/usr/bin/python3
"""Independent derivation of the shaft's element matrices (docs/model.md §18.1-§18.4).

For each case printed by the C++ program tests/shaft/dump_elements (argv[1]) this script
  1. solves the static Timoshenko beam (E I theta'' + kappa G A (w' - theta) = 0,
     w'' = theta') for the exact cubic w and quadratic theta with the four nodal values as
     data (Euler-Bernoulli: theta = w', the Hermite cubics) -- the shape functions;
  2. writes the energies of one element in the node dofs (u1, u2, psi1, psi2) of both
     nodes, with the conventions of §18.4: plane 1 carries (u1, theta1 = psi2), plane 2
     (u2, theta2 = -psi1);
        T = 1/2 int rho A (u1'^2 + u2'^2) + rho I (psi1'^2 + psi2'^2) dz      (dots: time)
            + int 2 rho I Omega psi1_dot psi2 dz                              (spin, 18.2.1)
        V = 1/2 int E I (theta1_z^2 + theta2_z^2) + kappa G A ((u1_z - theta1)^2 + (u2_z - theta2)^2) dz
     the spin term is the polar kinetic energy 1/2 I_p (Omega + psi1_dot psi2)^2 of a
     slice (rotations psi1 about a1, then psi2, then the spin), linear part;
  3. takes M = d2T/dq_dot2, K = d2V/dq2 and the gyroscopic matrix from Lagrange's
     equations, G Omega = P - P^T with P_ij = d2T_lin/dq_dot_i dq_j;
  4. adds the disc (mass, I_d, I_p by the same Lagrangian) and the bearing;
and compares with the C++ matrices entry by entry: |C++ - exact| <= 1e-13 max|exact|
(the C++ closed forms are evaluated in double with O(10) operations per entry).
Cowper's shear coefficient is re-stated here from the paper and compared to 1e-15.
Exact rational arithmetic (sympy) throughout. Exit 0 if all agree, 1 otherwise.
"""
import subprocess
import sys

import sympy as sp

z = sp.symbols('z')


def R(x):
    return sp.Rational(x)  # the exact value of the double


def shape_functions(L, EI, kGA):
    """w(z) and theta(z) as linear forms in the nodal values (w0, t0, w1, t1)."""
    a = sp.symbols('a0:4')
    b = sp.symbols('b0:3')
    q = sp.symbols('q0:4')
    w = sum(a[i] * z**i for i in range(4))
    if kGA is None:  # Euler-Bernoulli: theta = w'
        th = sp.diff(w, z)
        eqs = []
        unknowns = list(a)
    else:
        th = sum(b[i] * z**i for i in range(3))
        e1 = sp.expand(EI * sp.diff(th, z, 2) + kGA * (sp.diff(w, z) - th))
        e2 = sp.expand(sp.diff(w, z, 2) - sp.diff(th, z))
        eqs = sp.Poly(e1, z).all_coeffs() + sp.Poly(e2, z).all_coeffs()
        unknowns = list(a) + list(b)
    eqs += [w.subs(z, 0) - q[0], th.subs(z, 0) - q[1], w.subs(z, L) - q[2], th.subs(z, L) - q[3]]
    sol = sp.solve(eqs, unknowns, dict=True)[0]
    W = sp.expand(w.subs(sol))
    TH = sp.expand(th.subs(sol))
    return [sp.diff(W, qq) for qq in q], [sp.diff(TH, qq) for qq in q]


def element(case):
    L, D, d, E, rho, G = (R(case[k]) for k in ('L', 'D', 'd', 'E', 'rho', 'G'))
    A = sp.pi * (D**2 - d**2) / 4
    I = sp.pi * (D**4 - d**4) / 64
    kappa = None
    if G > 0:
        nu = E / (2 * G) - 1
        m2 = (d / D)**2
        # Cowper (1966), table 1, hollow circular section.
        kappa = 6 * (1 + nu) * (1 + m2)**2 / ((7 + 6 * nu) * (1 + m2)**2 + (20 + 12 * nu) * m2)
    Nw, Nt = shape_functions(L, E * I, None if kappa is None else kappa * G * A)
    # Dofs (u1, u2, psi1, psi2) at node 0 then node 1; symbols for positions and rates.
    q = sp.symbols('q0:8')
    qd = sp.symbols('v0:8')

    def plane(vec, which):
        n0, n1 = 0, 4
        if which == 1:
            idx = [(n0 + 0, 1), (n0 + 3, 1), (n1 + 0, 1), (n1 + 3, 1)]  # (u1, psi2)
        else:
            idx = [(n0 + 1, 1), (n0 + 2, -1), (n1 + 1, 1), (n1 + 2, -1)]  # (u2, -psi1)
        return [s * vec[i] for i, s in idx]

    def field(N, vec, which):
        return sum(Ni * ci for Ni, ci in zip(N, plane(vec, which)))

    u1, u2 = field(Nw, q, 1), field(Nw, q, 2)
    th1, th2 = field(Nt, q, 1), field(Nt, q, 2)
    u1d, u2d = field(Nw, qd, 1), field(Nw, qd, 2)
    th1d, th2d = field(Nt, qd, 1), field(Nt, qd, 2)
    psi1, psi2 = -th2, th1
    psi1d, psi2d = -th2d, th1d
    T = sp.integrate(sp.expand(rho * A * (u1d**2 + u2d**2) + rho * I * (psi1d**2 + psi2d**2)), (z, 0, L)) / 2
    Tlin = sp.integrate(sp.expand(2 * rho * I * psi1d * psi2), (z, 0, L))  # per unit Omega
    V = sp.integrate(sp.expand(E * I * (sp.diff(th1, z)**2 + sp.diff(th2, z)**2)), (z, 0, L)) / 2
    if kappa is not None:
        V += sp.integrate(sp.expand(kappa * G * A * ((sp.diff(u1, z) - th1)**2 + (sp.diff(u2, z) - th2)**2)),
                          (z, 0, L)) / 2
    M = sp.Matrix(8, 8, lambda i, j: sp.diff(T, qd[i], qd[j]))
    K = sp.Matrix(8, 8, lambda i, j: sp.diff(V, q[i], q[j]))
    P = sp.Matrix(8, 8, lambda i, j: sp.diff(Tlin, qd[i], q[j]))
    return M, K, P - P.T, sp.zeros(8, 8), kappa


def disc_and_bearing(M, K, Gm, C, disc, bearing):
    """Disc by the same Lagrangian: T = 1/2 m (u1d^2 + u2d^2) + 1/2 I_d (psi1d^2 + psi2d^2)
    + 1/2 I_p (Omega + psi1d psi2)^2; bearing springs and dampers to ground at node 1."""
    m, Ip, Id = (R(x) for x in disc)
    k, c, kt, ct = (R(x) for x in bearing)
    n = 4  # node 1
    for i in range(2):
        M[n + i, n + i] += m
        M[n + 2 + i, n + 2 + i] += Id
        K[n + i, n + i] += k
        C[n + i, n + i] += c
        K[n + 2 + i, n + 2 + i] += kt
        C[n + 2 + i, n + 2 + i] += ct
    # Tlin = I_p psi1d psi2: P[psi1, psi2] = I_p, G = P - P^T.
    Gm[n + 2, n + 3] += Ip
    Gm[n + 3, n + 2] -= Ip
    return M, K, Gm, C


def main():
    out = subprocess.run([sys.argv[1]], check=True, capture_output=True, text=True).stdout.splitlines()
    cases = []
    for line in out:
        f = line.split()
        if f[0] == 'case':
            cases.append({'name': f[1], 'L': float(f[2]), 'D': float(f[3]), 'd': float(f[4]), 'E': float(f[5]),
                          'rho': float(f[6]), 'G': float(f[7]), 'kappa': float(f[8]), 'Phi': float(f[9]),
                          'mats': {k: sp.zeros(8, 8) for k in ('mass', 'stiffness', 'gyroscopic', 'damping')}})
        else:
            cases[-1]['mats'][f[0]][int(f[1]), int(f[2])] = R(float(f[3]))
    failures = 0
    for case in cases:
        M, K, Gm, C, kappa = element(case)
        if case['name'] == 'disc_and_bearing':
            M, K, Gm, C = disc_and_bearing(M, K, Gm, C, (2.5, 0.03, 0.016), (1e7, 150.0, 2e4, 3.0))
        if kappa is not None:
            err = abs(float(kappa) - case['kappa']) / float(kappa)
            print(f"{case['name']}: shear coefficient {float(kappa):.16g}, C++ relative error {err:.2e}")
            failures += err > 1e-15
        for name, exact in (('mass', M), ('stiffness', K), ('gyroscopic', Gm), ('damping', C)):
            got = case['mats'][name]
            scale = max(abs(x) for x in exact) if any(x != 0 for x in exact) else 1
            worst = max(abs(sp.N(got[i, j] - exact[i, j], 30)) for i in range(8) for j in range(8)) / sp.N(scale, 30)
            ok = worst <= 1e-13
            failures += not ok
            print(f"{case['name']}: {name:10s} max |C++ - exact| / max|exact| = {float(worst):.2e} {'ok' if ok else 'FAIL'}")
    print('all agree' if failures == 0 else f'{failures} FAILED')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
