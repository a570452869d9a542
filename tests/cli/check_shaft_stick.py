#!/usr/bin/python3
"""coulomb-set balls on a flexible shaft (model.md §18.17), from the command line, against an
independent fixed-frame computation.

Reference (tests/reference/shaft_receptance.py): the shaft assembled in one plane from textbook Euler-Bernoulli elements (consistent
translational mass, rotary inertia rho I), discs and bearings, and its forward synchronous response
to a force turning with the rotor, W = [K - omega^2 (M_t - M_r) + i omega C]^-1 F: at spin = whirl
speed the gyroscopic moment turns every slope inertia I_d into I_d - I_p (beam: rho I - 2 rho I;
discs: I_d - I_p). The rotating frame sees that amplitude as a static deflection, so the node's
complex receptance h gives K_eff + i C_eff = 1/h and every node's |H_k| / |h| (18.17.2) without any
of the program's assembly, rotating-frame matrices or equivalent rigid balancer. Asserted: the
printed K_eff, C_eff and deflection ratios to 1e-9 relative (the two assemblies' rounding, ~1e-13,
amplified near a critical speed by at most the speed's distance to it); the rotor without balls
|h| omega^2 U to 1e-9; at the reported worst arrangement the reference's |q| = V and max_i |s_i| <= 1
+ 1e-9 (V lies on E's boundary or inside); where E is the whole torus V = |h| omega^2 (U + sum m l).
Then the CLI's contract: every format exits 0 without NaN/inf, each `sweep` row and `map` cell is
`equilibria` at its parameters (==, the same computation), 1 and 2 map threads give the same bytes,
and the commands that do not answer the combination refuse it (exit 2, the combination named,
nothing written).

usage: check_shaft_stick.py STABILITY_SCAN
"""
import csv
import filecmp
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

EXE = sys.argv[1]
failures = []

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "reference"))
from shaft_receptance import BALANCER, BALLS, SHAFT, U, receptances  # noqa: E402

SCENE = SHAFT + """[friction]
law = "coulomb-set"
mu = {mu}
[speed]
omega = {omega}
"""


def run(*args, code=0):
    r = subprocess.run([EXE, *args], capture_output=True, text=True)
    if r.returncode != code:
        failures.append(f"{' '.join(args)}: exit {r.returncode}, expected {code}\n{r.stderr}")
    return r


def rel(a, b):
    return abs(a - b) / max(abs(a), abs(b), 1e-300)


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


RES = ["--stick-columns", "96", "--stick-area-tolerance", "1e-7"]  # the contract part: a coarser set, cheaper


def equilibria(scene, sets, extra=()):
    args = ["equilibria", scene, "--format", "json", *extra]
    for s in sets:
        args += ["--set", s]
    return json.loads(run(*args).stdout)


with tempfile.TemporaryDirectory() as tmp:
    # --- the reference, at speeds below, near and above the first critical speeds, two mu
    for omega, mu in ((150.0, 2e-3), (900.0, 1e-4), (900.0, 3e-3), (2500.0, 1e-4)):
        scene = f"{tmp}/s.toml"
        with open(scene, "w") as f:
            f.write(SCENE.format(mu=mu, omega=omega))
        js = equilibria(scene, [])
        h = receptances(omega)
        hb = h[BALANCER]
        z = 1 / hb
        sh, st = js["shaft"], js["stick_set"]
        where = f"omega={omega} mu={mu}"
        if rel(sh["dynamic_stiffness"][0], z.real) > 1e-9 or rel(sh["dynamic_stiffness"][1], z.imag) > 1e-9:
            failures.append(f"{where}: K_eff + i C_eff {sh['dynamic_stiffness']} != reference {z}")
        for k, r in enumerate(sh["deflection_ratio"]):
            if rel(r, abs(h[k]) / abs(hb)) > 1e-9:
                failures.append(f"{where}: node {k} ratio {r} != reference {abs(h[k]) / abs(hb)}")
        if rel(st["bare_rotor_q_abs"], abs(hb) * omega**2 * U) > 1e-9:
            failures.append(f"{where}: bare rotor {st['bare_rotor_q_abs']} != {abs(hb) * omega ** 2 * U}")
        beta = st["worst_beta"]
        W = U + sum(m * l * complex(math.cos(b), math.sin(b)) for (m, l), b in zip(BALLS, beta))
        q = hb * omega**2 * W
        s = [(q.real * math.sin(b) - q.imag * math.cos(b)) / (mu * l) for (m, l), b in zip(BALLS, beta)]
        if rel(st["worst_q_abs"], abs(q)) > 1e-9:
            failures.append(f"{where}: V {st['worst_q_abs']} != reference |q| {abs(q)} at its beta")
        if max(abs(x) for x in s) > 1 + 1e-9:
            failures.append(f"{where}: the worst arrangement is outside E by the reference (max |s| {max(map(abs, s))})")
        if st["whole_torus"] and rel(st["worst_q_abs"], abs(hb) * omega**2 * (U + sum(m * l for m, l in BALLS))) > 1e-9:
            failures.append(f"{where}: whole torus but V != |h| omega^2 (U + sum m l)")
        worst = max(sh["deflection_ratio"])
        if rel(sh["worst_deflection"], worst * st["worst_q_abs"]) > 1e-12:
            failures.append(f"{where}: worst deflection is not ratio x V")
        print(f"{where}: K_eff + i C_eff = {z:.9g}, V = {st['worst_q_abs']:.6g} m, area {st['area']:.6g}, "
              f"worst node {sh['worst_node']} ({worst:.4g} x)")

    # --- every format, no NaN/inf (in islands, and on the whole torus)
    scene, whole = f"{tmp}/s.toml", f"{tmp}/whole.toml"
    with open(scene, "w") as f:
        f.write(SCENE.format(mu=1e-4, omega=900.0))
    with open(whole, "w") as f:
        f.write(SCENE.format(mu=2e-3, omega=150.0))
    for fmt, where in (("table", scene), ("csv", whole), ("json", whole)):
        out = run("equilibria", where, "--format", fmt, *RES).stdout
        if any(bad in out.lower() for bad in ("nan", "inf,", " inf")):
            failures.append(f"equilibria --format {fmt}: NaN or inf in the output")

    # --- sweep rows and map cells are equilibria at their parameters (the same doubles)
    run("sweep", scene, "--param", "omega", "--from", "850", "--to", "950", "--steps", "1", "--no-chart", "-o", f"{tmp}/sw",
        *RES)
    for row in rows(f"{tmp}/sw/sweep_stick_omega.csv"):
        js = equilibria(scene, [f"omega={row['omega']}"], RES)
        for key in ("area", "worst_q_abs", "worst_q_abs_any", "bare_rotor_q_abs"):
            if float(row[key]) != js["stick_set"][key]:
                failures.append(f"sweep omega={row['omega']}: {key} {row[key]} != equilibria {js['stick_set'][key]!r}")
        if float(row["worst_deflection"]) != js["shaft"]["worst_deflection"] or \
                float(row["K_eff"]) != js["shaft"]["dynamic_stiffness"][0]:
            failures.append(f"sweep omega={row['omega']}: the shaft columns differ from equilibria")
    for threads in ("1", "2"):
        run("map", scene, "--x", "omega:850:950:2", "--y", "mu:1e-4:1e-4:1", "--threads", threads, "--quiet",
            "--no-chart", "--long", "-o", f"{tmp}/m{threads}", *RES)
    for name in ("summary_omega_mu.csv", "map_omega_mu.csv"):
        if not filecmp.cmp(f"{tmp}/m1/{name}", f"{tmp}/m2/{name}", shallow=False):
            failures.append(f"map {name} differs between 1 and 2 threads")
    for row in rows(f"{tmp}/m1/summary_omega_mu.csv"):
        js = equilibria(scene, [f"omega={row['omega']}", f"mu={row['mu']}"], RES)
        if float(row["worst_q_abs"]) != js["stick_set"]["worst_q_abs"] or \
                float(row["worst_deflection_any"]) != js["shaft"]["worst_deflection_any"]:
            failures.append(f"map cell ({row['ix']}, {row['iy']}) differs from equilibria")

    # --- a smooth coulomb law on the shaft: its dry-friction verdict is this set (the same doubles,
    # model.md §14.10: the verdict computes what it prints as the full scan does)
    smooth = f"{tmp}/smooth.toml"
    with open(smooth, "w") as f:
        f.write(SCENE.format(mu=1e-4, omega=900.0).replace('law = "coulomb-set"', 'law = "coulomb"\nkappa = 100.0'))
    dry = json.loads(run("equilibria", smooth, "--format", "json", *RES).stdout)["dry_friction"]
    js = equilibria(scene, [], RES)
    for key in ("area", "worst_q_abs", "worst_q_abs_any", "bare_rotor_q_abs"):
        if dry[key] != js["stick_set"][key]:
            failures.append(f"coulomb on the shaft: dry_friction {key} {dry[key]!r} != the coulomb-set set's {js['stick_set'][key]!r}")
    if dry["shaft"]["worst_deflection"] != js["shaft"]["worst_deflection"]:
        failures.append("coulomb on the shaft: the verdict's worst deflection differs from the coulomb-set set's")

    # --- what does not answer the combination refuses it, naming it; nothing written
    for args in (["continue", scene, "--param", "omega", "--to", "1000", "-o", f"{tmp}/c"], ["simulate", scene, "--balls", "1,2", "-o", f"{tmp}/x"],
                 ["basin", scene, "-o", f"{tmp}/b"]):
        r = run(*args, code=2)
        if "coulomb-set balls on a flexible shaft" not in r.stderr:
            failures.append(f"{args[0]}: the refusal does not name the combination: {r.stderr.strip()}")
        if os.path.exists(args[-1]):
            failures.append(f"{args[0]}: wrote {args[-1]} although refused")
    r = run("sweep", scene, "--param", "k", "--from", "1e3", "--to", "2e3", "--steps", "2", "-o", f"{tmp}/k",
            code=2)
    if "[[bearing]]" not in r.stderr or os.path.exists(f"{tmp}/k"):
        failures.append(f"sweep --param k on a shaft: {r.stderr.strip()}")

for f in failures:
    print("FAIL", f)
print("ok" if not failures else f"{len(failures)} failures")
sys.exit(1 if failures else 0)
