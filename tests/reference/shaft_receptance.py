"""The small flexible rotor of the shaft checks (four Euler-Bernoulli elements, two discs, two
bearings, two balls; tests/scenes/composed/shaft_*.toml) as a scene text and its forward synchronous
receptance, assembled here independently of the program (model.md §18.17, (18.17.2)).

Reference: the shaft assembled in one plane from textbook Euler-Bernoulli elements (consistent
translational mass, rotary inertia rho I), discs and bearings, and its forward synchronous response
to a force turning with the rotor, W = [K - omega^2 (M_t - M_r) + i omega C]^-1 F: at spin = whirl
speed the gyroscopic moment turns every slope inertia I_d into I_d - I_p (beam: rho I - 2 rho I;
discs: I_d - I_p). The rotating frame sees that amplitude as a static deflection, so the balancer
node's complex receptance h gives K_eff + i C_eff = 1/h.
"""
import math

import numpy as np

ELEMENT = dict(length=0.1, outer=0.012, inner=0.004, E=2.1e11, rho=7800.0)  # four of them, nodes 0..4
DISCS = [(2, 0.12, 2.0e-4, 1.0e-4), (4, 0.3, 6.0e-4, 3.2e-4)]  # node, mass, I_p, I_d
BEARINGS = [(0, 2.0e5, 20.0, 0.0, 0.0), (3, 3.0e5, 30.0, 5.0, 0.01)]  # node, k, c, k_psi, c_psi
BALLS = [(3.3e-5, 0.018), (3.6e-5, 0.0182)]  # m, l
U, BALANCER = 6.0e-7, 2

# The scene text up to its [friction] table (the shaft, discs, bearings and balls).
SHAFT = f"""[rotor]
unbalance = {U}
[shaft]
balancer_node = {BALANCER}
[[shaft.element]]
length = 0.4
outer_diameter = {ELEMENT['outer']}
inner_diameter = {ELEMENT['inner']}
youngs_modulus = {ELEMENT['E']}
density = {ELEMENT['rho']}
segments = 4
""" + "".join(f"""[[disc]]
node = {n}
mass = {m}
polar_inertia = {ip}
transverse_inertia = {id_}
""" for n, m, ip, id_ in DISCS) + "".join(f"""[[bearing]]
node = {n}
stiffness = {k}
damping = {c}
tilt_stiffness = {kp}
tilt_damping = {cp}
""" for n, k, c, kp, cp in BEARINGS) + "".join(f"""[[ball]]
mass = {m}
race_radius = {l}
radius = 1.0e-3
""" for m, l in BALLS)


def receptances(omega):
    """H_k of every node's translation to a unit force at the balancer node (fixed frame, forward synchronous)."""
    nodes = 5
    size = 2 * nodes  # (w, theta) per node
    K = np.zeros((size, size), complex)
    L, D, d = ELEMENT["length"], ELEMENT["outer"], ELEMENT["inner"]
    A, I = math.pi * (D**2 - d**2) / 4, math.pi * (D**4 - d**4) / 64
    EI, rA, rI = ELEMENT["E"] * I, ELEMENT["rho"] * A, ELEMENT["rho"] * I
    ke = EI / L**3 * np.array([[12, 6 * L, -12, 6 * L], [6 * L, 4 * L * L, -6 * L, 2 * L * L],
                               [-12, -6 * L, 12, -6 * L], [6 * L, 2 * L * L, -6 * L, 4 * L * L]])
    mt = rA * L / 420 * np.array([[156, 22 * L, 54, -13 * L], [22 * L, 4 * L * L, 13 * L, -3 * L * L],
                                  [54, 13 * L, 156, -22 * L], [-13 * L, -3 * L * L, -22 * L, 4 * L * L]])
    mr = rI / (30 * L) * np.array([[36, 3 * L, -36, 3 * L], [3 * L, 4 * L * L, -3 * L, -L * L],
                                   [-36, -3 * L, 36, -3 * L], [3 * L, -L * L, -3 * L, 4 * L * L]])
    w2 = omega * omega
    for e in range(4):
        idx = np.arange(2 * e, 2 * e + 4)
        # forward synchronous whirl: slope inertia rho I - 2 rho I (the polar part turns it over)
        K[np.ix_(idx, idx)] += ke - w2 * (mt - mr)
    for n, m, ip, id_ in DISCS:
        K[2 * n, 2 * n] -= w2 * m
        K[2 * n + 1, 2 * n + 1] -= w2 * (id_ - ip)
    K[2 * BALANCER, 2 * BALANCER] -= w2 * sum(m for m, _ in BALLS)  # the balls move with the node
    for n, k, c, kp, cp in BEARINGS:
        K[2 * n, 2 * n] += k + 1j * omega * c
        K[2 * n + 1, 2 * n + 1] += kp + 1j * omega * cp
    f = np.zeros(size, complex)
    f[2 * BALANCER] = 1.0
    u = np.linalg.solve(K, f)
    return u[0::2]
