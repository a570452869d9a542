#!/usr/bin/python3
"""Independent reference for the stick set of coulomb-set balls on an unround race (docs/model.md
§20.5), against `stability-scan equilibria SCENE --format json` ("stick_set").

How it differs from the C++ route (a loop over the grid with the path point of (11.1.1)-(11.1.4)
per ball and angle, a breadth-first flood fill with the torus wrap):
  * the path p_i(beta) = l_i(beta) e^{i beta} and its derivative p_i' by numpy on the whole
    grid at once, p_i' by the complex step of l_i (no hand derivative);
  * the ball's stick condition from the force balance of a ball at rest on its path: the
    tangential component of the centrifugal force m omega^2 (q + p_i) along the unit tangent
    p_i'/|p_i'| must not exceed mu_i N_i = mu_i m_i l_i omega^2;
  * the rotor at rest from (k - M omega^2 + i c omega) q = omega^2 (U + sum m_i p_i);
  * components by scipy.ndimage.label, the wrap in both angles by joining the labels of the
    first and last rows and columns.
Checks (the same grid of G points per angle as the C++ run reports): the area within 2 cells,
V_E and V (over the component holding the anchor, the smooth equilibrium listed in the C++
"balanced_points") to 1e-12 relative, and s_i = 0 at every smooth equilibrium the C++ lists
(within 1e-6: the listed angles carry 16 digits).
Exit 0 on agreement, 1 on a mismatch, 2 on bad input.

Usage: composed_stick_reference.py SCENE.toml --json EQUILIBRIA.json
"""
import argparse
import json
import os
import sys
import tomllib

import numpy as np
from scipy import ndimage

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from composed_simulation_reference import harmonics, scene_balls  # noqa: E402 (the scene reading only)


def radius(h, l, beta):
    e, f = l + 0 * beta, 1 + 0 * beta
    for k, eps, phi in h:
        if k == 1:
            d = l * eps
            e = d * np.cos(beta - phi) + np.sqrt(l * l - d * d * np.sin(beta - phi) ** 2)
        else:
            f = f + eps * np.cos(k * beta - phi)
    return e * f


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("--json", required=True)
    a = ap.parse_args(argv)
    with open(a.scene, "rb") as fh:
        scene = tomllib.load(fh)
    with open(a.json) as fh:
        S = json.load(fh)["stick_set"]
    balls = scene_balls(scene)
    if len(balls) != 2:
        print("the reference handles two balls")
        return 2
    H = harmonics(scene, balls)
    rot, w = scene["rotor"], float(scene["speed"]["omega"])
    mu = [b.get("mu", scene["friction"].get("mu")) for b in balls]
    m = [b["mass"] for b in balls]
    l = [b["race_radius"] for b in balls]
    M = rot["mass"] + sum(m)
    G = w * w / complex(rot["stiffness"] - M * w * w, rot["damping"] * w)

    def path(i, beta):
        ell = radius(H[i], l[i], beta)
        h = 1e-30
        dell = np.imag(radius(H[i], l[i], beta + 1j * h)) / h
        e = np.exp(1j * beta)
        return ell * e, (dell + 1j * ell) * e

    def evaluate(b1, b2):
        p1, d1 = path(0, b1)
        p2, d2 = path(1, b2)
        q = G * (rot["unbalance"] + m[0] * p1 + m[1] * p2)
        s = []
        for p, dp, i in ((p1, d1, 0), (p2, d2, 1)):
            tangent = dp / np.abs(dp)
            force = m[i] * w * w * np.real(np.conj(tangent) * (q + p))  # along the path
            s.append(force / (mu[i] * m[i] * l[i] * w * w))
        return q, s

    n_grid = S["grid_points_per_angle"]
    g = 2 * np.pi * np.arange(n_grid) / n_grid
    B1, B2 = np.meshgrid(g, g, indexing="ij")
    q, s = evaluate(B1, B2)
    inside = (np.abs(s[0]) <= 1) & (np.abs(s[1]) <= 1)
    labels, count = ndimage.label(inside)
    parent = list(range(count + 1))

    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for x, y in list(zip(labels[0, :], labels[-1, :])) + list(zip(labels[:, 0], labels[:, -1])):
        if x and y:
            parent[find(x)] = find(y)
    roots = np.vectorize(lambda v: find(v) if v else 0)(labels)
    cell = (2 * np.pi / n_grid) ** 2
    area = inside.sum() * cell
    qa = np.abs(q)
    v_e = qa[inside].max()
    ok = True
    print(f"area {area:.9g} (C++ {S['area']:.9g}), components {len(set(roots[inside].tolist()))} (C++ {S['components']})")
    if abs(area - S["area"]) > 2 * cell:
        print("area differs by more than 2 cells")
        ok = False
    if abs(v_e - S["worst_q_abs_any"]) > 1e-12 * v_e:
        print(f"V_E {v_e:.12g} against C++ {S['worst_q_abs_any']:.12g}")
        ok = False
    eqs = S["smooth_equilibria"]
    for k, e in enumerate(eqs):
        qe, se = evaluate(np.array(e["beta"][0]), np.array(e["beta"][1]))
        if max(abs(float(se[0])), abs(float(se[1]))) > 1e-6:
            print(f"{e['family']}: s = ({float(se[0]):.3g}, {float(se[1]):.3g}) is not 0: not an equilibrium")
            ok = False
    anchors = [k for c in S["component_list"] for k in c["balanced_points"]]
    if S["balanced_exists"]:
        e = eqs[anchors[0] - 1]
        idx = tuple(int(round(b / (2 * np.pi / n_grid))) % n_grid for b in e["beta"])
        root = roots[idx]
        v = qa[(roots == root) & inside].max()
        print(f"V {v:.12g} (C++ {S['worst_q_abs']:.12g}) over the component of {e['family']}")
        if root == 0 or abs(v - S["worst_q_abs"]) > 1e-12 * v:
            ok = False
    print("agree" if ok else "MISMATCH")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
