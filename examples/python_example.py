#!/usr/bin/env python3
"""The abu Python module on the default scene: equilibria, a continuation in omega, a
stability map and a simulation (docs/python.md shows this run's output).

    cmake --build build            # builds build/python/abu
    PYTHONPATH=build/python /usr/bin/python3 examples/python_example.py
"""
import pathlib

import numpy as np

import abu

root = pathlib.Path(__file__).resolve().parents[1]
scene = abu.load_scene(root / "data" / "scenes" / "default.toml")
print(scene)

# Every equilibrium at omega = 900 rad/s with its spectrum (the CLI's `equilibria`).
eq = abu.equilibria(scene)
print("\nequilibria at omega =", eq.omega, "rad/s")
for i in range(len(eq)):
    print(f"  {eq.family[i]:9} {eq.member[i]}  |q| = {eq.q_abs[i]:.3e} m  beta = {np.round(eq.beta[i], 6)} rad"
          f"  {eq.stability[i]:8}  abscissa {eq.spectral_abscissa[i]: .6e} 1/s")
slowest = eq.eigenvalues[0][np.argmin(np.abs(eq.eigenvalues[0]))]
print("  balanced 1: slowest eigenvalue", slowest, "1/s, condition number",
      eq.condition[0][np.argmin(np.abs(eq.eigenvalues[0]))])

# The branches from 50 to 2000 rad/s (the CLI's `continue`) and their Hopf points.
run = abu.continue_branches(abu.load_scene(root / "data" / "scenes" / "default.toml", ["omega=50"]), "omega", 2000)
print("\n", run, sep="")
for b in run.branches:
    print(" ", b)
hb = run.special_points.select(run.special_points.label == "HB")
for k in range(len(hb)):
    print(f"  HB on branch {hb.branch[k]} ({hb.family[k]}): omega = {hb.parameter[k]:.10g} rad/s, "
          f"omega_H = {hb.frequency[k]:.6g} rad/s (rotating frame), l1 = {hb.lyapunov[k]:.3e}")

# A stability map over omega and the friction coefficient (the CLI's `map`).
m = abu.map(scene, x=("omega", 50, 2000, 40), y=("mu", 1e-4, 0.1, 20, "log"))
print("\n", m, sep="")
print("  cells with a stable balanced state:", int(np.nansum(m.balanced_stable)), "of", m.n_stable.size)
first = m.x[np.argmax((m.balanced_stable == 1).any(axis=1))]
print(f"  lowest omega with a stable balanced state on the grid: {first:.6g} rad/s")

# From balls at rest at 2 and 4 rad, 1 s at 900 rad/s (the CLI's `simulate`).
sim = abu.simulate(scene, 1.0, balls=[2.0, 4.0])
print("\n", sim, sep="")
print(f"  outcome {sim.summary.outcome}, settle time {sim.summary.settle_time} s, max |q| {sim.summary.max_q_abs:.3e} m")
print("  end state:", sim.x_end)

# Bad input raises abu.InputError with the CLI's message.
try:
    scene.set("omega", -1)
except abu.InputError as e:
    print("\nInputError:", e)
