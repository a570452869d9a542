#!/usr/bin/python3
"""Independent reference for `simulate` on a flexible shaft (docs/model.md §18.16, §18.20).

usage: shaft_simulation_reference.py STABILITY_SCAN SCENE [METHOD]

The program integrates the shaft in the frame ROTATING with it (model.md (18.16.2)); this
script integrates the same machine in the FIXED frame, from its own Lagrangian:
  * the element matrices M, K, G of tests/reference/shaft_elements.py (exact sympy
    integration of the beam energies, independent of the C++ closed forms), assembled here,
    with the disc (m, I_d, I_p) and the bearings (k, c, or an anisotropic bearing's fixed-frame
    K_f, C_f: model.md §18.19, tests/reference/shaft_aniso_reference.py) of the scene;
  * the spin energy of a slice or disc in the isotropic form 1/2 I_p (Omega + (psi1' psi2 -
    psi1 psi2')/2)^2, so that at a varying speed the shaft gains (Omega'/2) G u;
  * the balls as point masses at z_b + l_i e^{i alpha_i} (z_b = u1 + i u2 of the balancer
    node) with the rolling spin energy 1/2 I_i (Omega - (l_i/r_i)(alpha_i' - Omega))^2,
    I_i = (j_i - 1) m_i r_i^2, viscous friction F_i = -d l_i (alpha_i' - Omega) on alpha_i;
  * the unbalance force U (Omega^2 - i Omega') e^{i theta} at the balancer node.
A scene with [race] (an unround race, model.md §18.20) puts ball i's centre at
z_b + e^{i theta} p_i(beta_i) instead, p_i = l_i(beta) e^{i beta} the path of (11.1.1)-(11.1.2)
(path_radius of composed_simulation_reference.py, written from the formula), with the spin
energy 1/2 (j_i - 1) m_i (r_i Omega - s_i' beta_i')^2 and the viscous Rayleigh function
1/2 d s_i'^2 beta_i'^2; each ball's Lagrangian in (X, Y, beta_i) is differentiated by sympy and
its mass rows and forces added at the balancer node's (u1, u2) and beta_i. Such a scene is
integrated with METHOD (default DOP853: the shaft is not stiff, and Radau's difference
Jacobians of the sympy field cost minutes).
It runs the program (rk8pd, rtol 1e-10) at constant speed and on a ramp, integrates the fixed
frame with scipy's Radau (rtol 1e-11), rotates the balancer node's translation into the
rotating frame, q = R(-theta) z_b, beta_i = alpha_i - theta, and compares at every sample:
    |q_prog - q_ref| <= 1e-8 (L + |q|),   |beta_prog - beta_ref| <= 1e-8 rad.
The program's global error is within ~8 rtol = 8e-10 of the scaled size (model.md §15.1),
the reference's within a few 1e-11, and the transformation adds rounding of Omega t ~ 1e-14
rad: 1e-8 leaves a factor ~10 for the growth of errors over the run (measured: <= 2e-12 on q,
<= 1.1e-11 rad on beta). Exit 0 if both agree, 1 otherwise.
"""
import os
import subprocess
import sys
import tempfile
import tomllib

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from shaft_elements import element  # noqa: E402  (exact element matrices, sympy)
from composed_simulation_reference import harmonics, path_radius  # noqa: E402  (the race's paths, (11.1.1))


def assemble(scene):
    """Fixed-frame M, K, C, G of the shaft with discs and bearings (model.md §18.4)."""
    elems = []
    for sec in scene['shaft']['element']:
        for _ in range(sec.get('segments', 1)):
            elems.append({'L': sec['length'] / sec.get('segments', 1), 'D': sec['outer_diameter'],
                          'd': sec.get('inner_diameter', 0.0), 'E': sec['youngs_modulus'], 'rho': sec['density'],
                          'G': sec.get('shear_modulus', 0.0)})
    nodes = len(elems) + 1
    ns = 4 * nodes
    M, K, C, G = (np.zeros((ns, ns)) for _ in range(4))
    cache = {}
    for e, el in enumerate(elems):
        key = tuple(sorted(el.items()))
        if key not in cache:
            Me, Ke, Ge, _, _ = element(el)
            cache[key] = tuple(np.array(X.evalf(30), dtype=float) for X in (Me, Ke, Ge))
        Me, Ke, Ge = cache[key]
        sl = slice(4 * e, 4 * e + 8)
        M[sl, sl] += Me
        K[sl, sl] += Ke
        G[sl, sl] += Ge
    for disc in scene['disc']:
        k = 4 * disc['node']
        M[k, k] += disc['mass']
        M[k + 1, k + 1] += disc['mass']
        M[k + 2, k + 2] += disc['transverse_inertia']
        M[k + 3, k + 3] += disc['transverse_inertia']
        G[k + 2, k + 3] += disc['polar_inertia']
        G[k + 3, k + 2] -= disc['polar_inertia']
    for b in scene['bearing']:
        k = 4 * b['node']
        if 'stiffness_x' in b:  # an anisotropic bearing: K_f, C_f on the fixed axes (model.md §18.19)
            K[k:k + 2, k:k + 2] += [[b['stiffness_x'], b.get('stiffness_xy', 0.0)],
                                    [b.get('stiffness_xy', 0.0), b['stiffness_y']]]
            C[k:k + 2, k:k + 2] += [[b['damping_x'], b.get('damping_xy', 0.0)],
                                    [b.get('damping_xy', 0.0), b['damping_y']]]
        else:
            for i in range(2):
                K[k + i, k + i] += b['stiffness']
                C[k + i, k + i] += b['damping']
        for i in range(2):
            K[k + 2 + i, k + 2 + i] += b.get('tilt_stiffness', 0.0)
            C[k + 2 + i, k + 2 + i] += b.get('tilt_damping', 0.0)
    return M, K, C, G, nodes


class Speed:
    """omega(t) linear from w0 at rate alpha until w1, then held; theta(t) its integral."""

    def __init__(self, w0, w1=None, alpha=0.0):
        self.w0, self.w1 = w0, (w0 if w1 is None else w1)
        self.alpha = 0.0 if self.w1 == w0 else abs(alpha) * np.sign(self.w1 - w0)
        self.t1 = 0.0 if self.alpha == 0 else (self.w1 - w0) / self.alpha

    def omega(self, t):
        return self.w0 + self.alpha * t if t < self.t1 else self.w1

    def omega_dot(self, t):
        return self.alpha if t < self.t1 else 0.0

    def theta(self, t):
        if t < self.t1:
            return self.w0 * t + 0.5 * self.alpha * t * t
        return self.w0 * self.t1 + 0.5 * self.alpha * self.t1**2 + self.w1 * (t - self.t1)


def race_ball(h, m, l, r, j, d):
    """Ball on its unround path in the fixed frame: (Mi, fi), the 3 x 3 mass rows and the forces
    of Lagrange's equations in (X, Y, beta) (X, Y the balancer node's fixed-frame translation),
    lambdified in (X, Y, beta, X', Y', beta', theta, Omega, Omega')."""
    X, Y, b, dX, dY, db, th, Om, dOm = sp.symbols('X Y b dX dY db theta Omega dOmega', real=True)
    ell = path_radius(h, l, b)
    px, py = ell * sp.cos(b), ell * sp.sin(b)
    dpx, dpy = sp.diff(px, b), sp.diff(py, b)
    c, s = sp.cos(th), sp.sin(th)
    # d/dt (Z + R(theta) p(beta)) = Z' + Omega R' p + R p' beta'
    vx = dX + Om * (-s * px - c * py) + (c * dpx - s * dpy) * db
    vy = dY + Om * (c * px - s * py) + (s * dpx + c * dpy) * db
    speed_sq = dpx**2 + dpy**2
    T = m * (vx**2 + vy**2) / 2 + (j - 1) * m * (r * Om - sp.sqrt(speed_sq) * db) ** 2 / 2
    D = d * speed_sq * db**2 / 2
    q, dq = [X, Y, b], [dX, dY, db]
    pL = [sp.diff(T, v) for v in dq]
    Mi = sp.Matrix([[sp.diff(p, v) for v in dq] for p in pL])
    fi = sp.Matrix([sp.diff(T, qi) - sp.diff(D, dqi) - sum(sp.diff(p, qj) * dqj for qj, dqj in zip(q, dq))
                    - sp.diff(p, th) * Om - sp.diff(p, Om) * dOm for qi, dqi, p in zip(q, dq, pL)])
    args = [X, Y, b, dX, dY, db, th, Om, dOm]
    return sp.lambdify(args, Mi.tolist(), 'math', cse=True), sp.lambdify(args, list(fi), 'math', cse=True)


def reference(scene, speed, beta0, times, method='Radau'):
    M, K, C, G, nodes = assemble(scene)
    ns = 4 * nodes
    b = 4 * scene['shaft']['balancer_node']
    balls = scene['ball']
    n = len(balls)
    j = 1.4 if scene.get('rolling', False) else 1.0
    m = np.array([x['mass'] for x in balls])
    l = np.array([x['race_radius'] for x in balls])
    r = np.array([x['radius'] for x in balls])
    d_visc = scene['friction']['d']
    U = scene['rotor']['unbalance']
    dim = ns + n

    A0 = np.zeros((dim, dim))  # the configuration's mass matrix without the balls' coupling
    A0[:ns, :ns] = M
    A0[b, b] += m.sum()
    A0[b + 1, b + 1] += m.sum()
    A0[ns:, ns:] = np.diag(j * m * l * l)
    ml = m * l
    balls = np.arange(ns, dim)

    race = 'race' in scene
    if race:  # the balls on their paths: their whole share from race_ball, beta relative to the rotor
        A0[b, b] -= m.sum()
        A0[b + 1, b + 1] -= m.sum()
        A0[ns:, ns:] = 0.0
        ball_models = [race_ball(h, m[i], l[i], r[i], j, d_visc) for i, h in enumerate(harmonics(scene, scene['ball']))]

    def rhs_race(t, y):
        u, be, ud, bed = y[:ns], y[ns:dim], y[dim:dim + ns], y[dim + ns:]
        W, Wd, th = speed.omega(t), speed.omega_dot(t), speed.theta(t)
        A = A0.copy()
        f = np.empty(dim)
        f[:ns] = -(C @ ud) - W * (G @ ud) - 0.5 * Wd * (G @ u) - K @ u
        f[b] += U * (W * W * np.cos(th) + Wd * np.sin(th))
        f[b + 1] += U * (W * W * np.sin(th) - Wd * np.cos(th))
        f[ns:] = 0.0
        for i, (Mi, fi) in enumerate(ball_models):
            args = (u[b], u[b + 1], be[i], ud[b], ud[b + 1], bed[i], th, W, Wd)
            idx = [b, b + 1, ns + i]
            A[np.ix_(idx, idx)] += np.array(Mi(*args), float)
            f[idx] += np.array(fi(*args), float)
        return np.concatenate([y[dim:], np.linalg.solve(A, f)])

    def rhs(t, y):
        if race:
            return rhs_race(t, y)
        u, al, ud, ald = y[:ns], y[ns:dim], y[dim:dim + ns], y[dim + ns:]
        W, Wd, th = speed.omega(t), speed.omega_dot(t), speed.theta(t)
        sa, ca = np.sin(al), np.cos(al)
        A = A0.copy()
        A[b, balls] = A[balls, b] = -ml * sa
        A[b + 1, balls] = A[balls, b + 1] = ml * ca
        f = np.empty(dim)
        f[:ns] = -(C @ ud) - W * (G @ ud) - 0.5 * Wd * (G @ u) - K @ u
        f[b] += U * (W * W * np.cos(th) + Wd * np.sin(th)) + ml @ (ald**2 * ca)
        f[b + 1] += U * (W * W * np.sin(th) - Wd * np.cos(th)) + ml @ (ald**2 * sa)
        f[ns:] = l * (-d_visc * l * (ald - W)) + (j - 1) * ml * (r + l) * Wd
        return np.concatenate([y[dim:], np.linalg.solve(A, f)])

    y0 = np.zeros(2 * dim)
    y0[ns:dim] = beta0  # theta(0) = 0
    y0[dim + ns:] = 0.0 if race else speed.omega(0.0)  # the balls at rest relative to the rotor
    # Absolute tolerances in each component's natural size (L for translations, L per shaft
    # length for tilts, rad for angles; rates times omega), as the program's error control.
    L = (U + np.sum(m * l)) / (sum(x['mass'] for x in scene['disc'] if x['node'] == b // 4) + m.sum())
    length = sum(x['length'] for x in scene['shaft']['element'])
    size = np.array([L if i % 4 < 2 else L / length for i in range(ns)] + [1.0] * n)
    atol = 1e-11 * np.concatenate([size, size * speed.w1])
    breaks = [0.0] + ([speed.t1] if 0 < speed.t1 < times[-1] else []) + [times[-1]]
    out = []
    for a, z in zip(breaks[:-1], breaks[1:]):
        ts = sorted(set([t for t in times if a <= t <= z] + [z]))  # z: the next segment's start
        sol = solve_ivp(rhs, (a, z), y0, method=method, rtol=1e-11, atol=atol,
                        t_eval=ts, dense_output=False)
        assert sol.success, sol.message
        for k, t in enumerate(sol.t):
            if t in times and (not out or t > out[-1][0]):
                out.append((t, sol.y[:, k].copy()))
        y0 = sol.y[:, -1]
    rows = []
    for t, y in out:
        th = speed.theta(t)
        c, s = np.cos(th), np.sin(th)
        q1 = c * y[b] + s * y[b + 1]
        q2 = -s * y[b] + c * y[b + 1]
        rows.append([t, q1, q2] + list(y[ns:dim] - (0.0 if race else th)))
    return np.array(rows), m, l, U


def read_csv(path):
    lines = [x for x in open(path) if not x.startswith('#')]
    head = lines[0].strip().split(',')
    data = np.array([[float(v) if v else np.nan for v in x.strip().split(',')] for x in lines[1:]])
    return head, data


def main():
    with tempfile.TemporaryDirectory() as work:
        with open(sys.argv[2], 'rb') as fh:
            race = 'race' in tomllib.load(fh)
        method = sys.argv[3] if len(sys.argv) > 3 else ('DOP853' if race else 'Radau')
        return compare(sys.argv[1], sys.argv[2], work, method)


def compare(prog, scene_path, work, method='Radau'):
    with open(scene_path, 'rb') as fh:
        scene = tomllib.load(fh)
    w = scene['speed']['omega']
    beta0 = [0.5, 2.0, 4.0][:len(scene['ball'])]
    # The ramp from omega/2 to omega at 30 omega / s ends at t = 1/60 s, inside the run.
    cases = [('constant', Speed(w), []), ('ramp', Speed(0.5 * w, w, 30.0 * w), ['--ramp', f'{0.5 * w}:{w}:{30.0 * w}'])]
    failures = 0
    for name, speed, extra in cases:
        out = os.path.join(work, name)
        cmd = [prog, 'simulate', scene_path, '--balls', ','.join(str(x) for x in beta0), '--t-end', '0.025', '--every',
               '5e-4', '--rtol', '1e-10', '--method', 'rk8pd', '--no-chart', '--quiet', '-o', out] + extra
        subprocess.run(cmd, check=True)
        head, data = read_csv(os.path.join(out, 'simulation.csv'))
        ref, m, l, U = reference(scene, speed, np.array(beta0), list(data[:, 0]), method)
        assert len(ref) == len(data), (len(ref), len(data))
        n = len(beta0)
        disc = [x for x in scene['disc'] if x['node'] == scene['shaft']['balancer_node']][0]
        L = (U + np.sum(m * l)) / (disc['mass'] + np.sum(m))
        q = data[:, [head.index('q1'), head.index('q2')]]
        beta = data[:, [head.index(f'beta{i + 1}') for i in range(n)]]
        size = L + np.hypot(ref[:, 1], ref[:, 2])
        eq = np.max(np.abs(q - ref[:, 1:3]) / size[:, None])
        eb = np.max(np.abs(beta - ref[:, 3:]))
        ok = eq <= 1e-8 and eb <= 1e-8
        failures += not ok
        print(f"{name}: {len(ref)} samples to t = {ref[-1, 0]:.3g} s; max |dq| / (L + |q|) = {eq:.2e}, "
              f"max |dbeta| = {eb:.2e} rad {'ok' if ok else 'FAIL'}")
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
