#!/usr/bin/python3
"""`basin` on a flexible shaft (docs/model.md §18.21), from the commands' outputs:
  * a round race (two balls on the four-element test shaft, 600 rad/s): the header's attractors
    are exactly the balanced states `equilibria` calls stable; every cell the settle test ends
    lies within the settle radius of the state it names (ball angles; |q| at the balancer node
    against L); one cell's end equals `simulate` from the same start to the same time with the
    same samples (1e-9: one code);
  * race runout on the shaft: the attractors are the race's stable equilibria on the shaft
    (`equilibrium K`), the cells within the radius of the one they name;
  * anisotropic bearings: no attractor (their Floquet multipliers are not computed, and the
    header says so); every cell judged at t_end;
  * nothing non-finite in any file.

Usage: check_basin_shaft.py BINARY SCENES_DIR
"""
import csv
import json
import math
import os
import re
import sys
import tempfile
import tomllib

from check_basin_composed import RADIUS, run  # the settle radius, a command that must succeed


def view_scale(scene):
    """L of the balancer's view: (U + sum m l) / (balancer disc's mass + sum m)."""
    balls = scene["ball"]
    node = scene["shaft"]["balancer_node"]
    disc = sum(d["mass"] for d in scene["disc"] if d["node"] == node)
    return (scene["rotor"]["unbalance"] + sum(b["mass"] * b["race_radius"] for b in balls)) / (
        disc + sum(b["mass"] for b in balls))


def basin(binary, path, out, problems, t_end="10"):
    run(binary, "basin", path, "--grid", "3", "--t-end", t_end, "--threads", "2", "--no-chart", "--quiet", "-o", out)
    for name in ("basin.csv", "basin_fractions.csv", "basin.json"):
        body = open(os.path.join(out, name)).read().lower().replace("not_settled", "")
        if re.search(r"\bnan\b|\binf\b", body):
            problems.append(f"{path}: {name} holds a non-finite value")
    lines = open(os.path.join(out, "basin.csv")).read().splitlines()
    named = next((c for c in lines if c.startswith("# attractors of the settle test")), "").split(": ", 1)[-1]
    return lines, named, list(csv.DictReader(x for x in lines if not x.startswith("#")))


def check_cells(path, rows, targets, L, problems):
    """targets: label -> (beta, q_abs) of each attractor the header names."""
    for r in rows:
        if r["by_settle_test"] == "0":
            continue
        where = f"{path} cell ({r['i']}, {r['j']})"
        key = f"{r['attractor']} {r['member']}"
        if key not in targets:
            problems.append(f"{where}: {key} is not an attractor of the header {sorted(targets)}")
            continue
        beta, q_abs = targets[key]
        far = max(abs(math.remainder(float(r[f"beta{k + 1}_end"]) - b, 2 * math.pi)) for k, b in enumerate(beta))
        dq = abs(float(r["q_abs_end"]) - q_abs) / L
        if far > RADIUS or dq > RADIUS:
            problems.append(f"{where}: {key}, but its end lies {far:.3g} rad and {dq:.3g} L from it")


def main():
    binary, scenes = sys.argv[1], sys.argv[2]
    problems = []
    race_scene = os.path.join(scenes, "shaft", "race_four_elements.toml")
    aniso_scene = os.path.join(scenes, "shaft", "aniso_four_elements.toml")
    with tempfile.TemporaryDirectory() as tmp:
        # The race's shaft without its race: two balls on a round race.
        round_scene = os.path.join(tmp, "round.toml")
        text = open(race_scene).read()
        open(round_scene, "w").write(text[:text.index("[race]")])
        for path in (round_scene, race_scene):
            with open(path, "rb") as f:
                scene = tomllib.load(f)
            L = view_scale(scene)
            states = json.loads(run(binary, "equilibria", path, "--format", "json"))["equilibria"]
            out = os.path.join(tmp, os.path.basename(path) + ".out")
            lines, named, rows = basin(binary, path, out, problems)
            targets, expected = {}, []
            is_race = "race" in scene
            count = {}
            for s in states:
                if s["verdict"] != "stable":
                    continue
                label = "equilibrium" if is_race else s["family"]
                count[label] = count.get(label, 0) + 1
                key = f"{label} {s['member'] if is_race else count[label]}"
                expected.append(key)
                targets[key] = (s["beta"], s["q_abs"])
            if named != ", ".join(expected):
                problems.append(f"{path}: attractors '{named}', the stable states of equilibria {expected}")
            by_test = [r for r in rows if r["by_settle_test"] == "2"]
            if len(by_test) < len(rows) - 1:
                problems.append(f"{path}: only {len(by_test)} of {len(rows)} cells ended by the settle test")
            check_cells(path, rows, targets, L, problems)
            # One cell again by `simulate`: the same start, end time and samples (off the diagonal:
            # two balls that start together part only by rounding, which the printed angles lose).
            r = [x for x in by_test if x["i"] != x["j"]][-1]
            summary = os.path.join(tmp, "s.json")
            run(binary, "simulate", path, "--balls", f"{r['beta1_0']},{r['beta2_0']}", "--t-end", r["t_end"],
                "--every", "0.005", "--no-chart", "--quiet", "-o", os.path.join(tmp, "sim"), "--summary", summary)
            end = json.load(open(summary))["state_end"]
            diff = max(abs(math.remainder(float(r[f"beta{k + 1}_end"]) - end[2 + k], 2 * math.pi)) for k in range(2))
            diff = max(diff, abs(float(r["q_abs_end"]) - math.hypot(end[0], end[1])) / L)
            if diff > 1e-7:
                problems.append(f"{path}: cell ({r['i']}, {r['j']}) ends {diff:.3g} from simulate's run to its t_end")
            print(f"{os.path.basename(path)}: attractors {named}; {len(by_test)} of {len(rows)} cells by the settle test")
        lines, named, rows = basin(binary, aniso_scene, os.path.join(tmp, "aniso"), problems, "1")
        if named != "none stable" or not any("Floquet multipliers are not computed" in x for x in lines):
            problems.append(f"{aniso_scene}: attractors '{named}', expected none with the reason in the header")
        if any(r["by_settle_test"] != "0" for r in rows):
            problems.append(f"{aniso_scene}: a cell ended by the settle test with no attractor")
        print(f"aniso_four_elements.toml: {sorted({r['attractor'] for r in rows})} at t_end")
    if problems:
        print("\n".join(problems))
        return 1
    print("basin on a flexible shaft: attractors and ends agree with equilibria and simulate")
    return 0


if __name__ == "__main__":
    sys.exit(main())
