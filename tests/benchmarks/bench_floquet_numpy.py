#!/usr/bin/python3
"""numpy side of bench_floquet: RK4 monodromy of x' = J(t) x over pi/omega (800 steps, as
needed for ~1e-11 in the viscous case), timed; prints the ratio to the C++ verdict time.
Usage: bench_floquet_numpy.py J_FILE CPP_SECONDS [CPP_CELL_SECONDS STATES]
With the map cell's time, also the ratio of a numpy map cell (STATES monodromies) to it."""
import sys
import time

import numpy as np


def main():
    with open(sys.argv[1]) as f:
        omega, n = f.readline().split()
        omega, n = float(omega), int(n)
        rows = np.array([[float(v) for v in f.readline().split()] for _ in range(3 * n)])
    J0, Jc, Js = rows[:n], rows[n:2 * n], rows[2 * n:]
    cpp = float(sys.argv[2])

    def J(t):
        return J0 + np.cos(2 * omega * t) * Jc + np.sin(2 * omega * t) * Js

    def monodromy(steps=800):
        T = np.pi / omega
        h = T / steps
        Phi = np.eye(n)
        for k in range(steps):
            t = k * h
            A1, A2, A3 = J(t), J(t + h / 2), J(t + h)
            k1 = A1 @ Phi
            k2 = A2 @ (Phi + h / 2 * k1)
            k3 = A2 @ (Phi + h / 2 * k2)
            k4 = A3 @ (Phi + h * k3)
            Phi = Phi + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        return np.linalg.eigvals(Phi)

    reps = 5
    t0 = time.perf_counter()
    for _ in range(reps):
        rho = monodromy()
    t = (time.perf_counter() - t0) / reps
    print(f"numpy RK4-800 monodromy {1e3 * t:.3g} ms (max |rho| = {max(abs(rho)):.12f}): "
          f"{t / cpp:.1f} x the C++ Floquet verdict (magnus route)")
    if len(sys.argv) > 4:
        cell, states = float(sys.argv[3]), int(sys.argv[4])
        print(f"numpy map cell ({states} monodromies, equilibria not counted) {1e3 * states * t:.3g} ms: "
              f"{states * t / cell:.1f} x the C++ anisotropic map cell")


if __name__ == "__main__":
    main()
