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
count whatever the machine's load) and their ratio to the old binary's.
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
    return 0


if __name__ == "__main__":
    sys.exit(main())
