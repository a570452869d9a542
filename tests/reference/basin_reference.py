#!/usr/bin/python3
"""Independent reference for `stability-scan basin` (docs/model.md §15.5): the equations of
motion at constant speed ((9.1)-(9.4) with omega' = 0, i.e. (3.10)) written out again here
in numpy (not from the C++ model: the accelerations are solved from the three equations as
printed, per cell), integrated by classical RK4 at a fixed step for every cell of the grid at
once, and each end state classified by the rules of model.md §15.2 written again here.

The scene (not one of data/): a viscous two-ball balancer (d = 2e-3 N s/m... as below) at
400 rad/s = 1.6 omega_n, where the two mirror balanced states are the stable attractors and
the diagonal beta1 = beta2 (balls together) is an invariant set that ends in the aligned
state `++`. Grid 12 x 12 over [0, 2 pi)^2, t_end 20 s.

Agreement: every cell whose reference class equals that of its 4 edge neighbours (periodic grid)
must get the same class from the program (balanced: the same mirror state, told by the end
angle of ball 1; aligned: the same pattern). Cells next to a basin boundary (some neighbour
in another reference class) are not compared: there a start is within one cell of the
separatrix, and classifying it asks for more than either integration's accuracy guarantees.
At least half of the cells must be compared (the test is not vacuous).

usage: basin_reference.py BINARY
"""
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

M_R, K, C, U = 0.12, 7500.0, 2.0, 5.0e-7
MB, LB, RB, JB, DB = 3.0e-5, 0.018, 1.0e-3, 1.4, 2.0e-3
OMEGA, T_END, CELLS = 400.0, 20.0, 12

SCENE = f"""rolling = true
[rotor]
mass = {M_R}
stiffness = {K}
damping = {C}
unbalance = {U}
[[ball]]
mass = {MB}
race_radius = {LB}
radius = {RB}
[[ball]]
mass = {MB}
race_radius = {LB}
radius = {RB}
[friction]
law = "viscous"
d = {DB}
[speed]
omega = {OMEGA}
"""


def rhs(x):
    """x: (cells, 8) = q1, q2, b1, b2, q1', q2', b1', b2' in the rotating frame."""
    w = OMEGA
    M = M_R + 2 * MB
    a = MB * LB
    q1, q2, b, qd1, qd2, bd = x[:, 0], x[:, 1], x[:, 2:4], x[:, 4], x[:, 5], x[:, 6:8]
    P1 = 2 * w * qd2 + w * w * q1
    P2 = -2 * w * qd1 + w * w * q2
    s, co = np.sin(b), np.cos(b)
    n = x.shape[0]
    A = np.zeros((n, 4, 4))
    rh = np.zeros((n, 4))
    A[:, 0, 0] = M
    A[:, 1, 1] = M
    rh[:, 0] = M * P1 - C * (qd1 - w * q2) - K * q1 + w * w * U
    rh[:, 1] = M * P2 - C * (qd2 + w * q1) - K * q2
    for i in range(2):
        A[:, 0, 2 + i] = -a * s[:, i]
        rh[:, 0] += a * (bd[:, i] + w) ** 2 * co[:, i]
        A[:, 1, 2 + i] = a * co[:, i]
        rh[:, 1] += a * (bd[:, i] + w) ** 2 * s[:, i]
        # ball i: j m l b'' = -d l b' + m ((q1'' - P1) sin - (q2'' - P2) cos)
        A[:, 2 + i, 2 + i] = JB * MB * LB
        A[:, 2 + i, 0] = -MB * s[:, i]
        A[:, 2 + i, 1] = MB * co[:, i]
        rh[:, 2 + i] = -DB * LB * bd[:, i] + MB * (-P1 * s[:, i] + P2 * co[:, i])
    acc = np.linalg.solve(A, rh[:, :, None])[:, :, 0]
    return np.concatenate([x[:, 4:8], acc], axis=1)


def integrate(x, h):
    for _ in range(int(round(T_END / h))):
        k1 = rhs(x)
        k2 = rhs(x + h / 2 * k1)
        k3 = rhs(x + h / 2 * k2)
        k4 = rhs(x + h * k3)
        x = x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    return x


def classify(x):
    """model.md §15.2 written again: balanced (which mirror state), aligned (pattern), other."""
    M = M_R + 2 * MB
    L = (U + 2 * MB * LB) / M
    gamma = math.acos(U / (2 * MB * LB))  # U + a (e^{i b1} + e^{i b2}) = 0: b = pi -+ gamma
    q = math.hypot(x[0], x[1])
    W = math.hypot(U + MB * LB * (math.cos(x[2]) + math.cos(x[3])), MB * LB * (math.sin(x[2]) + math.sin(x[3])))
    if max(abs(x[4]), abs(x[5])) / (L * OMEGA) > 1e-3 or max(abs(x[6]), abs(x[7])) / OMEGA > 1e-3:
        return "moving"
    if q <= 1e-2 * L and W <= 1e-2 * (U + 2 * MB * LB):
        return mirror(x[2], gamma)
    phi = math.atan2(x[1], x[0])
    if q > 0 and all(abs(math.sin(b - phi)) <= 1e-2 for b in x[2:4]):
        ref = math.cos(x[2] - phi)
        return "aligned:" + "".join("+" if math.cos(b - phi) * ref >= 0 else "-" for b in x[2:4])
    return "other"


def mirror(beta1, gamma):
    d_lo = abs(math.remainder(beta1 - (math.pi - gamma), 2 * math.pi))
    d_hi = abs(math.remainder(beta1 - (math.pi + gamma), 2 * math.pi))
    return "balanced:lo" if d_lo < d_hi else "balanced:hi"


def main():
    binary = sys.argv[1]
    gamma = math.acos(U / (2 * MB * LB))
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "basin_viscous.toml")
        with open(scene, "w") as fh:
            fh.write(SCENE)
        out = os.path.join(tmp, "out")
        cmd = [binary, "basin", scene, "--grid", str(CELLS), "--t-end", str(T_END), "--threads", "2", "--no-chart",
               "--quiet", "-o", out]
        res = subprocess.run(cmd, capture_output=True, text=True)
        if res.returncode != 0:
            print(f"FAIL: {' '.join(cmd)}: exit {res.returncode}: {res.stderr}")
            return 1
        with open(os.path.join(out, "basin.csv")) as fh:
            lines = [l.rstrip("\n") for l in fh if not l.startswith("#")]
    head = lines[0].split(",")
    col = {name: k for k, name in enumerate(head)}
    program = {}
    member_of_side = {}
    ok = True
    for line in lines[1:]:
        f = line.split(",")
        i, j = int(f[col["i"]]), int(f[col["j"]])
        label = f[col["attractor"]]
        if label == "balanced":
            side = mirror(float(f[col["beta1_end"]]), gamma)
            # The program's member numbers one mirror state consistently.
            if f[col["member"]]:
                if member_of_side.setdefault(side, f[col["member"]]) != f[col["member"]]:
                    print(f"FAIL: cell ({i}, {j}): {side} has members {member_of_side[side]} and {f[col['member']]}")
                    ok = False
            label = side
        program[(i, j)] = label
    if len(program) != CELLS * CELLS:
        print(f"FAIL: {len(program)} cells in basin.csv, expected {CELLS * CELLS}")
        return 1

    x0 = np.zeros((CELLS * CELLS, 8))
    for i in range(CELLS):
        for j in range(CELLS):
            x0[i * CELLS + j, 2] = 2 * math.pi * i / CELLS
            x0[i * CELLS + j, 3] = 2 * math.pi * j / CELLS
    h = 4e-4  # h |lambda| <= 0.27 for the fastest mode (650 rad/s): RK4 well inside its stability region
    xe = integrate(x0, h)
    ref = {(i, j): classify(xe[i * CELLS + j]) for i in range(CELLS) for j in range(CELLS)}
    compared = agreed = 0
    for (i, j), r in sorted(ref.items()):
        near = any(ref[((i + di) % CELLS, (j + dj) % CELLS)] != r for di, dj in ((-1, 0), (1, 0), (0, -1), (0, 1)))
        if near:
            continue
        compared += 1
        if program[(i, j)] == r:
            agreed += 1
        else:
            print(f"FAIL: cell ({i}, {j}) beta = ({x0[i * CELLS + j, 2]:.4f}, {x0[i * CELLS + j, 3]:.4f}): "
                  f"program {program[(i, j)]}, reference {r}")
            ok = False
    counts = {}
    for r in ref.values():
        counts[r] = counts.get(r, 0) + 1
    print(f"reference: RK4 h = {h:g} s to t = {T_END:g} s; classes {counts}")
    print(f"{'ok  ' if ok else 'FAIL'} {agreed} of {compared} cells away from a basin boundary agree "
          f"({CELLS * CELLS - compared} next to a boundary not compared)")
    if compared < CELLS * CELLS // 2:
        print("FAIL: fewer than half of the cells compared")
        ok = False
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
