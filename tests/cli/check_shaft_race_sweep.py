#!/usr/bin/python3
"""`sweep` and `map` of balls on an unround race on a flexible shaft (model.md §18.18), from the
command line, against the physics computed independently.

Reference (tests/reference/shaft_receptance.py): the shaft's forward synchronous receptance h of the
balancer node, assembled in numpy from textbook elements, and the ball path of model.md (11.1.1),
(11.1.2) written here from the formula (an offset circle for the order-1 harmonic). Per row of the
sweep, with its reported beta:
  1. the balancer node's q = h omega^2 (U + sum m_i p_i(beta_i)) (the balls' centrifugal load on the
     shaft, (18.18.1)): to 1e-8 of |q| (the two assemblies' rounding, ~1e-13, amplified near a
     critical speed by the distance to it; the row's beta printed to 17 digits);
  2. every ball at rest on its path: the centrifugal force m omega^2 (q + p_i) has no component along
     the path's tangent p_i' (viscous friction is zero at rest), |t . (q + p_i)| <= 1e-9 |q + p_i|;
  3. the summary's q_bare = omega^2 U |h| to 1e-9; best_q_abs = the least |q| of the stable rows;
  4. the unroundness factor 0 gives the round race's equilibria of the same shaft (the program's
     other search, find_shaft_equilibria, through `equilibria`): the same |q| to 1e-9 (+ 1e-15 m for
     the balanced states' zero) and the same verdicts.
Then the map: 1 and 2 threads give the same bytes, every cell is the sweep's summary at that point and
its q_bare the reference's; and the contract: no NaN/inf in any file, the chart written, and k as a
sweep parameter or map axis refused (exit 2, the rule named, nothing written).

usage: check_shaft_race_sweep.py STABILITY_SCAN
"""
import cmath
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "reference"))
from shaft_receptance import BALANCER, BALLS, SHAFT, U, receptances  # noqa: E402

EXE = sys.argv[1]
failures = []
OFFSET = 5.5556e-5  # order-1 amplitude: the race's centre 1 um off the axis (tests/scenes/composed/shaft_runout.toml)
SCENE = SHAFT + f"""[friction]
law = "viscous"
d = 2.0e-6
[speed]
omega = 900.0
[race]
unroundness = [{{ order = 1, amplitude = {OFFSET}, phase = 0.0 }}]
"""


def run(*args, code=0):
    r = subprocess.run([EXE, *args], capture_output=True, text=True)
    if r.returncode != code:
        failures.append(f"{' '.join(args)}: exit {r.returncode}, expected {code}\n{r.stderr}")
    return r


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def path_point(beta, l):
    """p(beta) of model.md (11.1.1)-(11.1.2) with only the order-1 harmonic (phase 0), and its tangent."""
    d = l * OFFSET
    radius = lambda b: d * math.cos(b) + math.sqrt(l * l - d * d * math.sin(b) ** 2)
    h = 1e-6
    dr = (radius(beta + h) - radius(beta - h)) / (2 * h)  # l' by central difference: O(h^2 d) ~ 1e-18 m
    e = cmath.exp(1j * beta)
    return radius(beta) * e, (dr + 1j * radius(beta)) * e


def check_rows(table, summary, name):
    by_value = {}
    for r in table:
        by_value.setdefault(r[name], []).append(r)
    for s in summary:
        omega = float(s[name]) if name == "omega" else 900.0
        h = receptances(omega)[BALANCER]
        where = f"{name}={s[name]}"
        q_bare = abs(h) * omega**2 * U
        if abs(float(s["q_bare"]) - q_bare) > 1e-9 * q_bare:
            failures.append(f"{where}: q_bare {s['q_bare']}, reference {q_bare:.12g}")
        stable = []
        for r in by_value.get(s[name], []):
            betas = [float(r[f"beta{i + 1}"]) for i in range(len(BALLS))]
            points = [path_point(b, l) for b, (_, l) in zip(betas, BALLS)]
            w = U + sum(m * p for (m, _), (p, _) in zip(BALLS, points))
            q_ref = h * omega**2 * w
            q = complex(float(r["q1"]), float(r["q2"]))
            if abs(q - q_ref) > 1e-8 * abs(q_ref):
                failures.append(f"{where} equilibrium {r['equilibrium']}: q {q}, reference {q_ref}")
            for i, (p, t) in enumerate(points):
                along = abs((t.conjugate() * (q + p)).real) / abs(t)
                if along > 1e-9 * abs(q + p):
                    failures.append(f"{where} equilibrium {r['equilibrium']}: ball {i + 1} not at rest on its path "
                                    f"(tangential share {along / abs(q + p):.3g})")
            if r["stable"] == "1":
                stable.append(float(r["q_abs"]))
            if r["verdict"] == "stable" and r["stable"] != "1":
                failures.append(f"{where}: verdict stable but stable column {r['stable']}")
        best = s["best_q_abs"]
        if (best == "") != (not stable) or (stable and float(best) != min(stable)):
            failures.append(f"{where}: best_q_abs {best!r}, least stable |q| {min(stable) if stable else None}")


def no_nan(path):
    with open(path) as f:
        text = f.read().lower()
    if "nan" in text or "inf" in text.replace("infinite", ""):
        failures.append(f"{path}: NaN or inf written")


with tempfile.TemporaryDirectory() as tmp:
    scene = f"{tmp}/s.toml"
    with open(scene, "w") as f:
        f.write(SCENE)
    # 1-3: across the first critical speeds (~880 rad/s) in omega, and in U at 900 rad/s
    run("sweep", scene, "--param", "omega", "--from", "300", "--to", "1500", "--steps", "8", "-o", f"{tmp}/w")
    for p in ("sweep_omega.csv", "summary_omega.csv", "summary_omega.png"):
        if not os.path.exists(f"{tmp}/w/{p}"):
            failures.append(f"omega sweep: {p} not written")
    if not failures:
        no_nan(f"{tmp}/w/sweep_omega.csv")
        no_nan(f"{tmp}/w/summary_omega.csv")
        check_rows(rows(f"{tmp}/w/sweep_omega.csv"), rows(f"{tmp}/w/summary_omega.csv"), "omega")
    run("sweep", scene, "--param", "U", "--from", "2e-7", "--to", "1.2e-6", "--steps", "2", "--no-chart", "-o", f"{tmp}/u")
    if os.path.exists(f"{tmp}/u/summary_U.csv"):
        table, summary = rows(f"{tmp}/u/sweep_U.csv"), rows(f"{tmp}/u/summary_U.csv")
        for s in summary:  # q_bare scales with U
            q_bare = abs(receptances(900.0)[BALANCER]) * 900.0**2 * float(s["U"])
            if abs(float(s["q_bare"]) - q_bare) > 1e-9 * q_bare:
                failures.append(f"U={s['U']}: q_bare {s['q_bare']}, reference {q_bare:.12g}")
        if len(summary) != 3 or not table:
            failures.append(f"U sweep: {len(summary)} values, {len(table)} rows")
    # 4: the factor 0 is the round race: the same states as `equilibria` on the round shaft
    run("sweep", scene, "--param", "unroundness", "--from", "0", "--to", "1", "--steps", "1", "--no-chart",
        "-o", f"{tmp}/e")
    round_scene = f"{tmp}/round.toml"
    with open(round_scene, "w") as f:
        f.write(SCENE.split("[race]")[0])
    states = json.loads(run("equilibria", round_scene, "--format", "json").stdout)["equilibria"]
    if os.path.exists(f"{tmp}/e/sweep_unroundness.csv"):
        at_zero = [r for r in rows(f"{tmp}/e/sweep_unroundness.csv") if float(r["unroundness"]) == 0.0]
        ours = sorted((float(r["q_abs"]), r["verdict"]) for r in at_zero)
        theirs = sorted((s["q_abs"], s["verdict"]) for s in states)
        if len(ours) != len(theirs):
            failures.append(f"factor 0: {len(ours)} states, the round race has {len(theirs)}")
        for (qa, va), (qb, vb) in zip(ours, theirs):
            # 1e-15 m: the balanced state's |q| is zero to the rounding of micrometre deflections
            if abs(qa - qb) > 1e-9 * max(qa, qb) + 1e-15 or va != vb:
                failures.append(f"factor 0: |q| {qa:.12g} ({va}), round race {qb:.12g} ({vb})")
    # the map (omega x unroundness): 1 and 2 threads give the same bytes; every cell's summary is the
    # sweep's at that point (the same analysis), its q_bare the reference's
    grid = ("--x", "omega:300:1500:4", "--y", "unroundness:0:2:3", "--no-chart")
    run("map", scene, *grid, "--threads", "1", "-o", f"{tmp}/m1")
    run("map", scene, *grid, "--threads", "2", "-o", f"{tmp}/m2")
    name = "summary_omega_unroundness.csv"
    if os.path.exists(f"{tmp}/m1/{name}") and os.path.exists(f"{tmp}/m2/{name}"):
        with open(f"{tmp}/m1/{name}") as a, open(f"{tmp}/m2/{name}") as b:
            if a.read() != b.read():
                failures.append("map: 1 and 2 threads give different bytes")
        no_nan(f"{tmp}/m1/{name}")
        cells = rows(f"{tmp}/m1/{name}")
        if len(cells) != 12:
            failures.append(f"map: {len(cells)} cells, expected 12")
        for omega in ("300", "700", "1100", "1500"):
            run("sweep", scene, "--set", f"omega={omega}", "--param", "unroundness", "--from", "0", "--to", "2",
                "--steps", "2", "--no-chart", "-o", f"{tmp}/s{omega}")
            if not os.path.exists(f"{tmp}/s{omega}/summary_unroundness.csv"):
                continue
            for s in rows(f"{tmp}/s{omega}/summary_unroundness.csv"):
                cell = next((c for c in cells if c["omega"] == omega and float(c["unroundness"]) == float(s["unroundness"])), None)
                keys = ("equilibria", "stable", "unstable", "undetermined", "best_q_abs", "q_bare", "complete")
                if cell is None or any(cell[k] != s[k] for k in keys):
                    failures.append(f"map cell omega={omega} factor {s['unroundness']}: {cell}, sweep {s}")
            q_bare = abs(receptances(float(omega))[BALANCER]) * float(omega) ** 2 * U
            for c in (c for c in cells if c["omega"] == omega):
                if abs(float(c["q_bare"]) - q_bare) > 1e-9 * q_bare:
                    failures.append(f"map cell omega={omega}: q_bare {c['q_bare']}, reference {q_bare:.12g}")
    # the contract: a rigid rotor's parameter is refused before any work
    for args in (("sweep", scene, "--param", "k", "--from", "1e5", "--to", "2e5", "--steps", "2"),
                 ("map", scene, "--x", "k:1e5:2e5:2", "--y", "omega:300:400:2")):
        r = run(*args, "-o", f"{tmp}/k", code=2)
        if "flexible shaft" not in r.stderr or "'k'" not in r.stderr:
            failures.append(f"{args[0]} over k: {r.stderr.strip()}")
        if os.path.exists(f"{tmp}/k"):
            failures.append(f"{args[0]} over k: the output directory was written")

if failures:
    print("\n".join(failures))
    sys.exit(1)
print("sweep and map of an unround race on a flexible shaft: rows, summaries and the round-race limit agree with the reference")
