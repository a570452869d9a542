#!/usr/bin/python3
"""`map` on an unround race with an anisotropic support (docs/model.md §20.7), its contract on
tests/scenes/composed/oval_anisotropic.toml (two unequal balls, omega across the lower critical
speed sqrt(k_y / M) ~ 212 rad/s and well above it):
  * `--x omega:200:1100:2 --y U:4e-7:8e-7:2 --threads 2` exits 0; summary_omega_U.csv has the 4
    cells in order (ix outer), no NaN or inf, counts that add up (orbits + failed = equilibria,
    stable + unstable + marginal = orbits; at omega = 200 two orbits do not converge), and the
    chart is written;
  * every cell is what `equilibria --set omega=.. --set U=.. --format json` says at that point:
    the race's equilibria, the converged orbits by verdict, and best_q_abs the least q_abs_max
    of the stable orbits, to 1e-12 relative (the same computation: the map adds nothing to it
    but the bookkeeping, which is what this checks);
  * an unroundness axis (omega 650, 1100 x factor 0, 1): factor 1 gives the scene's cells; factor
    0 is the anisotropic support alone, as `equilibria` computes it by another path (its balanced
    states by Hill's Floquet multipliers, q = 0; its aligned states' orbits, best |q| to 1e-8);
  * k and c as axes are refused (exit 2: they are the anisotropic support's means), nothing
    written.
The orbits themselves are checked against an independent integration in reference/composed_orbits;
the tiles' independence of the thread count is the map driver's (map_contract, cli/shaft_race_sweep).
Usage: check_composed_map.py BINARY SCENE"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile


def rows(path):
    with open(path) as fh:
        return list(csv.DictReader(ln for ln in fh if not ln.startswith("#")))


def find(obj, key):
    """The first value of `key` anywhere in a JSON document."""
    if isinstance(obj, dict):
        if key in obj:
            return obj[key]
        obj = list(obj.values())
    if isinstance(obj, list):
        for v in obj:
            found = find(v, key)
            if found is not None:
                return found
    return None


def run_map(binary, scene, out, x, y, threads=1):
    return subprocess.run([binary, "map", scene, "--x", x, "--y", y, "--threads", str(threads), "--quiet", "-o", out],
                          capture_output=True, text=True)


def expected_cell(binary, scene, sets):
    args = [binary, "equilibria", scene, "--format", "json"]
    for s in sets:
        args += ["--set", s]
    run = subprocess.run(args, capture_output=True, text=True)
    if run.returncode != 0:
        raise RuntimeError(f"equilibria {sets}: exit {run.returncode}: {run.stderr}")
    doc = json.loads(run.stdout)
    cell = {"equilibria": find(doc, "unround_equilibria"), "orbits": 0, "stable": 0, "unstable": 0, "marginal": 0,
            "failed": 0, "best": None}
    return count_orbits(cell, find(doc, "periodic_orbits"))


def count_orbits(cell, orbits):
    """Adds the JSON `periodic_orbits` to the cell's counts: by verdict, not converged (no
    `stability` member), and the least q_abs_max of the stable ones."""
    for o in orbits or []:
        if "stability" not in o:
            cell["failed"] += 1
            continue
        cell["orbits"] += 1
        cell[o["stability"]] += 1
        if o["stability"] == "stable" and (cell["best"] is None or o["q_abs_max"] < cell["best"]):
            cell["best"] = o["q_abs_max"]
    return cell


def compare(fails, where, row, want, rel=1e-12):
    for k in ("equilibria", "orbits", "stable", "unstable", "marginal", "failed"):
        if int(row[k]) != want[k]:
            fails.append(f"{where}: {k} {row[k]}, equilibria says {want[k]}")
    got = float(row["best_q_abs"]) if row["best_q_abs"] else None
    if (got is None) != (want["best"] is None):
        fails.append(f"{where}: best_q_abs {row['best_q_abs']!r}, equilibria says {want['best']}")
    elif got is not None and abs(got - want["best"]) > max(rel * want["best"], 1e-15):
        fails.append(f"{where}: best_q_abs {got}, equilibria says {want['best']}")


def main(binary, scene):
    fails = []
    with tempfile.TemporaryDirectory() as tmp:
        one, fac, bad = (os.path.join(tmp, d) for d in ("one", "factor", "bad"))
        run = run_map(binary, scene, one, "omega:200:1100:2", "U:4e-7:8e-7:2", threads=2)
        if run.returncode != 0:
            return f"map exit {run.returncode}: {run.stderr}"
        path = os.path.join(one, "summary_omega_U.csv")
        text = open(path).read()
        if "nan" in text.lower() or "inf" in text.lower().replace("infinity", ""):
            fails.append("summary has a NaN or inf")
        if not os.path.getsize(os.path.join(one, "summary_omega_U.png")):
            fails.append("no chart")
        cells = rows(path)
        order = [(float(r["omega"]), float(r["U"])) for r in cells]
        if order != [(w, u) for w in (200.0, 1100.0) for u in (4e-7, 8e-7)]:
            fails.append(f"cells out of order: {order}")
        stable_somewhere = failed_somewhere = False
        for r in cells:
            where = f"cell omega={r['omega']}, U={r['U']}"
            if int(r["orbits"]) + int(r["failed"]) != int(r["equilibria"]):
                fails.append(f"{where}: orbits + failed != equilibria")
            if int(r["stable"]) + int(r["unstable"]) + int(r["marginal"]) != int(r["orbits"]):
                fails.append(f"{where}: the verdicts do not add up to the orbits")
            stable_somewhere |= int(r["stable"]) > 0
            failed_somewhere |= int(r["failed"]) > 0
            compare(fails, where, r, expected_cell(binary, scene, [f"omega={r['omega']}", f"U={r['U']}"]))
        if not stable_somewhere or not failed_somewhere:
            fails.append("no stable or no failed orbit in any cell: the comparison checked less than it should")

        run = run_map(binary, scene, fac, "omega:650:1100:2", "unroundness:0:1:2")
        # factor 1 at omega = 1100 is a cell of the map above; both omegas at factor 0
        if run.returncode != 0:
            fails.append(f"unroundness axis: exit {run.returncode}: {run.stderr}")
        else:
            by = {(float(r["omega"]), float(r["unroundness"])): r for r in rows(os.path.join(fac, "summary_omega_unroundness.csv"))}
            mine = {float(r["omega"]): r for r in cells if float(r["U"]) == 8e-7}  # the scene's U
            a, b = by[(1100.0, 1.0)], mine[1100.0]
            for k in ("equilibria", "orbits", "stable", "unstable", "marginal", "failed", "best_q_abs"):
                if a[k] != b[k]:
                    fails.append(f"omega=1100: factor 1 gives {k} {a[k]}, the scene's map {b[k]}")
            for w in (650.0, 1100.0):
                # Factor 0: the anisotropic support alone, whose `equilibria` reports its balanced
                # states by Hill's Floquet multipliers and its other states as orbits (§10.14): another
                # path, so the best |q| to 1e-8 relative (orbits) or 1e-15 m (a balanced state, q = 0).
                compare(fails, f"omega={w}, factor 0", by[(w, 0.0)], expected_round(binary, scene, w, tmp), 1e-8)

        for axis in ("k:8000:9000:2", "c:1:2:2"):
            run = run_map(binary, scene, bad, axis, "U:4e-7:8e-7:2")
            if run.returncode != 2 or "means" not in run.stderr or "anisotropic" not in run.stderr:
                fails.append(f"--x {axis}: exit {run.returncode}, {run.stderr.strip()!r}")
            if os.path.exists(bad) and os.listdir(bad):
                fails.append(f"--x {axis}: wrote {os.listdir(bad)}")
    return "; ".join(fails)


def expected_round(binary, scene, omega, tmp):
    """The factor-0 cell from `equilibria` of the scene with its [race] table left out (a round
    race on the anisotropic support): its balanced states (Floquet, q = 0) and its orbits."""
    lines, skip = [], False
    for ln in open(scene):
        if ln.strip().startswith("["):
            skip = ln.strip() == "[race]"
        if not skip:
            lines.append(ln)
    path = os.path.join(tmp, "round.toml")
    with open(path, "w") as fh:
        fh.writelines(lines)
    run = subprocess.run([binary, "equilibria", path, "--set", f"omega={omega}", "--format", "json"],
                         capture_output=True, text=True)
    if run.returncode != 0:
        raise RuntimeError(f"equilibria of the round race: exit {run.returncode}: {run.stderr}")
    doc = json.loads(run.stdout)
    balanced = find(doc, "balanced_states") or []
    cell = {"equilibria": len(balanced) + find(doc, "aligned_equilibria"), "orbits": len(balanced), "stable": 0,
            "unstable": 0, "marginal": 0, "failed": 0, "best": None}
    for b in balanced:
        cell[b["stability"]] += 1
        if b["stability"] == "stable":
            cell["best"] = 0.0
    return count_orbits(cell, find(doc, "periodic_orbits"))


if __name__ == "__main__":
    failure = main(sys.argv[1], sys.argv[2])
    if failure:
        print("FAIL:", failure)
        sys.exit(1)
    print("ok: the composed map's cells are equilibria's, thread-independent, k and c refused")
