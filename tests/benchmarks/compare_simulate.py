#!/usr/bin/python3
"""`stability-scan simulate` as a user runs it (the default 2000 samples, the CSV and the
summary), one binary against another on the same runs: the integration's wall time
(`stats.wall_seconds` of the summary, the median of alternating launches), its steps, the worst
sample against a reference run (the NEW binary at rtol 1e-12, its samples at the same times) in
the scaled norm of model.md §15.1, and the largest |q| against the reference's (relative).

    compare_simulate.py OLD_BINARY NEW_BINARY SOURCE_DIR [--repeat R] [--rtol T ...] [--instructions]

Each run is launched with the old binary at its default tolerance and with the new one at its
default and at every --rtol given (e.g. --rtol 1e-7 --rtol 1e-6). --instructions adds the
instructions executed inside simulate() (valgrind --tool=callgrind, once per run: the same
count whatever the machine's load) and their ratio to the old binary's. Then one `basin` run
(data/scenes/viscous.toml, 8 x 8 cells, its run-up to 20 s, one thread) with both binaries at
their defaults: the process's wall time, the instructions in simulate() over all cells, and
whether every cell's class is the same, with the largest change of a cell's max_q_abs.
"""
import argparse
import csv
import json
import math
import os
import statistics
import subprocess
import sys
import re
import tempfile
import time

RUNS = [  # name, scene (relative to SOURCE_DIR), arguments, omega_max [rad/s] (the scales of §15.1)
    ("coulomb 900 rad/s (stiff)", "data/scenes/default.toml",
     ["--from-equilibrium", "balanced", "--perturb", "0.3", "--t-end", "1"], 900.0),
    ("coulomb kappa 1e6 (stiff)", "data/scenes/default.toml",
     ["--set", "kappa=1e6", "--from-equilibrium", "balanced", "--perturb", "0.3", "--t-end", "1"], 900.0),
    ("coulomb run-up", "data/scenes/default.toml", ["--ramp", "150:350:1000", "--t-end", "0.3", "--balls", "2,4"], 350.0),
    ("viscous run-up", "data/scenes/viscous.toml", ["--ramp", "100:400:1000", "--t-end", "0.6", "--balls", "2,4"], 400.0),
]


def run(binary, scene, args, tmp, tag, callgrind=False):
    out = os.path.join(tmp, tag)
    js = out + ".json"
    cmd = [binary, "simulate", scene] + args + ["--no-chart", "--quiet", "-o", out, "--summary", js]
    if callgrind:
        cmd = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}.cg", "--toggle-collect=*abu::simulate<*"] + cmd
    res = subprocess.run(cmd, capture_output=True, text=True)
    if res.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}: exit {res.returncode}: {res.stderr}")
    with open(js) as fh:
        s = json.load(fh)
    with open(os.path.join(out, "simulation.csv")) as fh:
        rows = list(csv.reader(line for line in fh if not line.startswith("#")))
    head = rows[0]
    n = sum(1 for c in head if c.startswith("beta") and not c.startswith("beta_rel"))
    cols = [head.index(c) for c in ["q1", "q2"] + [f"beta{i}" for i in range(1, n + 1)] + ["dq1", "dq2"]
            + [f"dbeta{i}" for i in range(1, n + 1)]]
    samples = [(float(r[0]), [float(r[c]) for c in cols]) for r in rows[1:]]
    if callgrind:
        found = re.search(r"Collected : (\d+)", res.stderr)
        s["instructions"] = int(found.group(1)) if found else math.nan
    return s, samples


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("source")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--rtol", action="append", default=[])
    ap.add_argument("--instructions", action="store_true")
    a = ap.parse_args()
    print("| run | binary, rtol | method | steps | integration wall (median) | worst sample (scaled) | largest abs(q), "
          "relative | wall / old |" + (" instructions in simulate() | / old |" if a.instructions else ""))
    print("|---|---|---|---|---|---|---|---|" + ("---|---|" if a.instructions else ""))
    with tempfile.TemporaryDirectory() as tmp:
        for name, scene_rel, args, w_max in RUNS:
            scene = os.path.join(a.source, scene_rel)
            ref, ref_samples = run(a.new, scene, args + ["--rtol", "1e-12"], tmp, "ref")
            L = ref["displacement_scale"]
            configs = [("old, default", a.old, [])] + [("new, default", a.new, [])] + \
                [(f"new, {r}", a.new, ["--rtol", r]) for r in a.rtol]
            walls = {c[0]: [] for c in configs}
            last = {}
            for _ in range(a.repeat):  # alternate the binaries: the machine's load hits them alike
                for tag, binary, extra in configs:
                    s, samples = run(binary, scene, args + extra, tmp, "x")
                    walls[tag].append(s["stats"]["wall_seconds"])
                    last[tag] = (s, samples)
            n = (len(ref["state_end"]) - 4) // 2
            base = statistics.median(walls["old, default"])
            counts = {tag: run(binary, scene, args + extra, tmp, "cg", True)[0]["instructions"]
                      for tag, binary, extra in configs} if a.instructions else {}
            for tag, _, _ in configs:
                s, samples = last[tag]
                scale = [L, L] + [1.0] * n + [L * w_max, L * w_max] + [w_max] * n
                worst = math.inf if len(samples) != len(ref_samples) else max(
                    max(abs(x - y) / c for x, y, c in zip(sa[1], sb[1], scale)) for sa, sb in zip(samples, ref_samples))
                peak = abs(s["max_q_abs"] - ref["max_q_abs"]) / ref["max_q_abs"]
                med = statistics.median(walls[tag])
                extra = (f" {counts[tag] / 1e6:.1f} M | {counts[tag] / counts['old, default']:.2f} |"
                         if a.instructions else "")
                print(f"| {name} | {tag} | {s['method']} | {s['stats']['steps']} | {med * 1e3:.3g} ms | {worst:.2e} | "
                      f"{peak:.1e} | {med / base:.2f} |" + extra, flush=True)
    basin(a)
    return 0


def basin(a):
    args = ["basin", os.path.join(a.source, "data/scenes/viscous.toml"), "--grid", "8", "--ramp", "100:400:100",
            "--threads", "1", "--no-chart", "--quiet"]
    with tempfile.TemporaryDirectory() as tmp:
        walls = {"old": [], "new": []}
        for k in range(a.repeat):
            for tag, binary in (("old", a.old), ("new", a.new)):
                out = os.path.join(tmp, f"{tag}{k}")
                t0 = time.perf_counter()
                subprocess.run([binary] + args + ["-o", out], check=True, capture_output=True)
                walls[tag].append(time.perf_counter() - t0)
        rows = {}
        for tag in ("old", "new"):
            with open(os.path.join(tmp, f"{tag}0", "basin.csv")) as fh:
                rows[tag] = list(csv.DictReader(line for line in fh if not line.startswith("#")))
        same = all(x["attractor"] == y["attractor"] and x["member"] == y["member"] for x, y in zip(rows["old"], rows["new"]))
        dq = max(abs(float(x["max_q_abs"]) - float(y["max_q_abs"])) / float(x["max_q_abs"])
                 for x, y in zip(rows["old"], rows["new"]))
        steps = {tag: sum(int(r["steps"]) for r in rows[tag]) for tag in rows}
        counts = {}
        if a.instructions:
            for tag, binary in (("old", a.old), ("new", a.new)):
                res = subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={tmp}/{tag}.cg",
                                      "--toggle-collect=*abu::simulate<*", binary] + args + ["-o", f"{tmp}/cg{tag}"],
                                     capture_output=True, text=True, check=True)
                counts[tag] = int(re.search(r"Collected : (\d+)", res.stderr).group(1))
        old, new = statistics.median(walls["old"]), statistics.median(walls["new"])
        print(f"\nbasin (viscous, 8 x 8, run-up 100 -> 400 rad/s at 100 rad/s^2, 20 s, 1 thread): steps {steps['old']} -> "
              f"{steps['new']}, process wall {old:.2f} s -> {new:.2f} s ({new / old:.2f})"
              + (f", instructions in simulate() {counts['old'] / 1e6:.0f} M -> {counts['new'] / 1e6:.0f} M "
                 f"({counts['new'] / counts['old']:.2f})" if counts else "")
              + f"; every cell's class {'the same' if same else 'NOT the same'}, max_q_abs changed by at most "
              f"{dq:.1e} (relative)")


if __name__ == "__main__":
    sys.exit(main())
