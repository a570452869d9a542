#!/usr/bin/python3
"""`basin` on an unround race (docs/model.md §15.7): every cell that a run ended at an equilibrium
of the race names a stable equilibrium of `equilibria` at the same speed, and its end angles and
|q| lie within the settle radius of that equilibrium's (checked here from the two commands'
outputs, not from the basin's own test); the fractions add up to the grid; and an unround race
is refused by nothing but the combinations that are not modelled.

Usage: check_basin_unround.py BINARY SCENE
"""
import json
import math
import os
import subprocess
import sys
import tempfile


def main():
    binary, scene = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as out:
        run = subprocess.run([binary, "basin", scene, "--grid", "4x4", "--t-end", "6", "-o", out, "--no-chart", "--quiet"],
                             capture_output=True, text=True)
        if run.returncode != 0:
            print("basin failed:", run.stderr)
            return 1
        rows = [line.rstrip("\n").split(",") for line in open(os.path.join(out, "basin.csv")) if not line.startswith("#")]
        header, rows = rows[0], rows[1:]
        col = {name: k for k, name in enumerate(header)}
        eq = json.loads(subprocess.run([binary, "equilibria", scene, "--format", "json"], capture_output=True,
                                       text=True, check=True).stdout)
        fractions = json.load(open(os.path.join(out, "basin.json")))["fractions"]
    equilibria = eq["equilibria"]
    ok = len(rows) == 16 and abs(sum(fractions.values()) - 1) < 1e-9
    reached = 0
    for r in rows:
        if r[col["attractor"]] != "equilibrium":
            continue
        reached += 1
        e = equilibria[int(r[col["member"]]) - 1]
        ends = [float(r[col["beta1_end"]]), float(r[col["beta2_end"]])]
        # settle radius 1e-2 (scaled: angles in rad, q / L); 2e-2 allows the last samples' motion
        far = max(abs(math.remainder(a - b, 2 * math.pi)) for a, b in zip(ends, e["beta"]))
        if e["stability"] != "stable" or far > 2e-2 or abs(float(r[col["q_abs_end"]]) - e["q_abs"]) > 2e-2 * e["q_abs"] + 1e-8:
            print(f"cell {r[0]},{r[1]}: ended at equilibrium {r[col['member']]} ({e['stability']}), angles {far:.3g} rad away")
            ok = False
    if reached == 0:
        print("no cell reached an equilibrium of the race: the check tested nothing")
        ok = False
    print(f"{len(rows)} cells, {reached} at an equilibrium of the race; fractions {fractions}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
