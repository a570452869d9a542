#!/usr/bin/python3
"""`basin` on an unround race with an anisotropic support (docs/model.md §20.8), from the two
commands' outputs:
  * the header's attractors are exactly the orbits `equilibria` calls stable at the final speed;
  * every cell ends by the settle test on one of them ("orbit k"), its end |q| within the settle
    radius (scaled by L) of that orbit's |q| range over the period, its end angles within the
    radius of the orbit's angle range;
  * the fractions (CSV and JSON) are each orbit's share of the cells, "orbit k" by number, and
    add up to 1; one and two threads give the same bytes; nothing non-finite is written;
  * three balls with per-ball paths on the same support (every ball's start angle sampled) run
    and end on stable orbits of `equilibria` too.

Usage: check_basin_composed.py BINARY SCENES_DIR
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import tomllib

RADIUS = 1e-2  # the default settle radius (model.md §15.5)


def run(*args):
    r = subprocess.run(list(args), capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"{' '.join(args)}: exit {r.returncode}\n{r.stderr}")
    return r.stdout


def check(binary, scene, out, grid, threads, problems):
    run(binary, "basin", scene, "--grid", grid, "--t-end", "25", "--threads", str(threads), "--no-chart", "--quiet",
        "-o", out)
    with open(os.path.join(out, "basin.csv")) as f:
        text = f.read()
    for name in ("basin.csv", "basin_fractions.csv", "basin.json"):
        body = open(os.path.join(out, name)).read().lower()
        if "nan" in body.replace("not_settled", "") or "inf" in body.replace("info", ""):
            problems.append(f"{scene}: {name} holds a non-finite value")
    lines = text.splitlines()
    orbits = json.loads(run(binary, "equilibria", scene, "--format", "json"))["periodic_orbits"]
    stable = {k + 1: o for k, o in enumerate(orbits) if o["stability"] == "stable"}
    named = next((c for c in lines if c.startswith("# attractors of the settle test")), "").split(": ", 1)[-1]
    if named != ", ".join(f"orbit {k}" for k in stable):
        problems.append(f"{scene}: attractors '{named}', stable orbits of equilibria {list(stable)}")
    with open(scene, "rb") as f:
        s = tomllib.load(f)
    balls = s["ball"] if "ball" in s else [s["balls"]] * s["balls"]["count"]
    L = (s["rotor"]["unbalance"] + sum(b["mass"] * b["race_radius"] for b in balls)) / (
        s["rotor"]["mass"] + sum(b["mass"] for b in balls))
    rows = list(csv.DictReader(x for x in lines if not x.startswith("#")))
    count = {}
    for r in rows:
        where = f"{scene} cell ({r['i']}, {r['j']})"
        if r["attractor"] != "orbit" or r["by_settle_test"] != "2" or int(r["member"]) not in stable:
            problems.append(f"{where}: {r['attractor']} {r['member']} (by_settle_test {r['by_settle_test']})")
            continue
        k = int(r["member"])
        count[k] = count.get(k, 0) + 1
        o = stable[k]
        q = float(r["q_abs_end"])
        # |q| over the period lies in [2 mean - max, max] to first order in the variation
        low, high = 2 * o["q_abs_mean"] - o["q_abs_max"], o["q_abs_max"]
        if not (low - RADIUS * L <= q <= high + RADIUS * L):
            problems.append(f"{where}: end |q| {q:.6g} m outside orbit {k}'s range [{low:.6g}, {high:.6g}] m "
                            f"+- the radius {RADIUS * L:.3g} m")
        for b in range(len(balls)):
            beta = float(r[f"beta{b + 1}_end"])
            lo, hi = o["ball_min"][b], o["ball_max"][b]
            mid, half = (lo + hi) / 2, (hi - lo) / 2
            if abs(math.remainder(beta - mid, 2 * math.pi)) > half + RADIUS:
                problems.append(f"{where}: ball {b + 1} ends at {beta:.6f} rad, orbit {k}'s range [{lo:.6f}, "
                                f"{hi:.6f}] rad")
    fractions = json.load(open(os.path.join(out, "basin.json")))["fractions"]
    expected = {f"orbit {k}": c / len(rows) for k, c in count.items()}
    if set(fractions) != set(expected) or any(abs(fractions[k] - v) > 1e-6 for k, v in expected.items()):
        problems.append(f"{scene}: fractions {fractions}, counted {expected}")
    if abs(sum(fractions.values()) - 1) > 1e-5:
        problems.append(f"{scene}: fractions add up to {sum(fractions.values())}")
    return text, count


def main():
    binary, scenes = sys.argv[1], sys.argv[2]
    problems = []
    two = os.path.join(scenes, "composed", "oval_anisotropic.toml")
    three = os.path.join(scenes, "composed", "three_balls_oval_anisotropic.toml")
    with tempfile.TemporaryDirectory() as tmp:
        one_thread, count = check(binary, two, os.path.join(tmp, "t1"), "4", 1, problems)
        two_threads, _ = check(binary, two, os.path.join(tmp, "t2"), "4", 2, problems)
        if one_thread != two_threads or open(os.path.join(tmp, "t1", "basin.json")).read() != open(
                os.path.join(tmp, "t2", "basin.json")).read():
            problems.append("one and two threads give different bytes")
        if len(count) < 2:
            problems.append(f"the two-ball grid reached {sorted(count)}: the check needs two orbits to tell apart")
        _, count3 = check(binary, three, os.path.join(tmp, "n3"), "3", 2, problems)
    print(f"two balls: cells per orbit {count}; three balls: {count3}")
    if problems:
        print("\n".join(problems))
        return 1
    print("basin on an unround race with an anisotropic support: every cell on a stable orbit of equilibria")
    return 0


if __name__ == "__main__":
    sys.exit(main())
