#!/usr/bin/python3
"""`sweep` and `map` of coulomb-set scenes (model.md §14) against `equilibria`.

Every sweep row and every map cell is `equilibria`'s stick set at the same parameters and
resolution, so the figures must be the very same doubles (compared with ==, no tolerance:
the same code on the same inputs; the boundary curves, which sweep and map skip, do not
feed any figure). A map computed on 1 and on 2 threads must be the same bytes. Scenes:
tests/scenes/stick/merged.toml (two components), whole.toml (the whole torus),
tests/scenes/stick_n/three.toml (three balls, grid), kept cheap (a few seconds).

usage: check_stick_scan.py STABILITY_SCAN TESTS_DIR
"""
import csv
import filecmp
import json
import subprocess
import sys
import tempfile

EXE, TESTS = sys.argv[1], sys.argv[2]
FIGURES = ("area", "area_fraction", "worst_q_abs", "worst_q_abs_any", "mean_q_abs", "bare_rotor_q_abs")
failures = []


def run(*args):
    r = subprocess.run([EXE, *args], capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"{' '.join(args)}: exit {r.returncode}\n{r.stderr}")
    return r.stdout


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def equilibria(scene, sets, extra=()):
    args = ["equilibria", scene, "--format", "json", *extra]
    for s in sets:
        args += ["--set", s]
    return json.loads(run(*args))["stick_set"]


def compare(where, row, js):
    for key in FIGURES:
        if key == "worst_q_abs" and not js["balanced_exists"]:
            ok = row[key] == ""
        else:
            ok = float(row[key]) == js[key]
        if not ok:
            failures.append(f"{where}: {key} {row[key]} != equilibria {js[key]!r}")
    if int(row["components"]) != js["components"]:
        failures.append(f"{where}: components {row['components']} != {js['components']}")
    for i, s in enumerate(js["spread"] if js["balanced_exists"] else []):
        if float(row[f"spread{i + 1}"]) != s:
            failures.append(f"{where}: spread{i + 1} {row[f'spread{i + 1}']} != {s!r}")


with tempfile.TemporaryDirectory() as d:
    merged = f"{TESTS}/scenes/stick/merged.toml"
    whole = f"{TESTS}/scenes/stick/whole.toml"
    three = f"{TESTS}/scenes/stick_n/three.toml"

    # sweep of omega, two values: each row is equilibria at that omega
    run("sweep", merged, "--param", "omega", "--from", "780", "--to", "820", "--steps", "1", "--no-chart", "-o", f"{d}/s")
    for row in rows(f"{d}/s/sweep_stick_omega.csv"):
        compare(f"sweep omega={row['omega']}", row, equilibria(merged, [f"omega={row['omega']}"]))

    # map, two balls, 2 x 1 cells at a coarser resolution: each cell is equilibria with it
    res = ["--stick-columns", "400", "--stick-area-tolerance", "1e-8"]
    run("map", merged, "--x", "omega:790:810:2", "--y", "mu:7e-5:7e-5:1", "--threads", "1", "--quiet", "--no-chart",
        "-o", f"{d}/m", *res)
    for row in rows(f"{d}/m/summary_omega_mu.csv"):
        compare(f"map cell ({row['ix']}, {row['iy']})", row,
                equilibria(merged, [f"omega={row['omega']}", f"mu={row['mu']}"], res))

    # map, three balls (grid), one cell
    grid = ["--stick-grid", "8192"]
    run("map", three, "--x", "omega:800:800:1", "--y", "mu:6e-5:6e-5:1", "--quiet", "--no-chart", "-o", f"{d}/n", *grid)
    for row in rows(f"{d}/n/summary_omega_mu.csv"):
        compare("three-ball map cell", row, equilibria(three, [f"omega={row['omega']}", f"mu={row['mu']}"], grid))

    # 1 and 2 threads: the same bytes (summary and long CSV)
    for threads in ("1", "2"):
        run("map", whole, "--x", "omega:700:900:3", "--y", "mu:0.002:0.003:2", "--threads", threads, "--quiet",
            "--no-chart", "--long", "-o", f"{d}/t{threads}")
    for name in ("summary_omega_mu.csv", "map_omega_mu.csv"):
        if not filecmp.cmp(f"{d}/t1/{name}", f"{d}/t2/{name}", shallow=False):
            failures.append(f"{name} differs between 1 and 2 threads")

for f in failures:
    print("FAIL", f)
print("ok" if not failures else f"{len(failures)} failures")
sys.exit(1 if failures else 0)
